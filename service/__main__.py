from dexlab.cli import main

main()
