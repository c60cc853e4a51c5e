"""Figures of the kinematic-chain jobs: link graphs, the P/Q bar chart, the four-bar."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.figure import Figure

from tests.unit.common.test_figures import png_pixels, svg_strings
from worker.common.figures import figure_artifacts
from worker.families.chains import kinematics as c
from worker.families.chains.kinematics.fourbar import classify_four_bar, four_bar_poses
from worker.families.chains.plots import bars, fourbar
from worker.families.chains.plots import graphs as graph_plots

FIG_4B = graph_plots.ChainGraph(
    name="Fig 4b",
    links=("1", "2", "3", "4", "5", "6", "7"),
    polygonal=frozenset({"1", "4"}),
    joints=(("1", "2"), ("2", "3"), ("3", "4"), ("4", "5"), ("1", "5"), ("4", "6"), ("6", "7"),
            ("1", "7")),
    loops=(("1.a", "2", "3", "4.a", "5"), ("1.b", "5", "4.b", "6", "7"),
           ("1.c", "2", "3", "4.c", "6", "7")),
    loop_lengths=((6, 11, 10, 6, 5), (7, 5, 8, 7, 10), (9, 11, 10, 9, 7, 10)),
    caption="7 links, 8 joints, mobility 2",
)  # fmt: skip


def quad(name: str, lengths: tuple[float, ...]) -> graph_plots.ChainGraph:
    s = c.chain_structure(c.single_loop_chain(name, lengths))
    return graph_plots.ChainGraph(name, s.links, frozenset(), s.joints, s.loops,
                        tuple(tuple(map(float, loop)) for loop in s.loop_lengths))  # fmt: skip


def test_layout_puts_the_periphery_on_a_circle_and_inner_links_at_the_mean() -> None:
    xy = graph_plots.graph_layout(FIG_4B)
    rim = ["1", "2", "3", "4", "6", "7"]
    assert all(math.isclose(math.hypot(*xy[link]), 1.0) for link in rim)
    assert xy["1"] == pytest.approx((0.0, 1.0))  # the first peripheral link at the top
    mean = np.mean([xy["1"], xy["4"]], axis=0)
    assert xy["5"] == pytest.approx(tuple(mean))


def test_chain_graphs_render_with_loops_and_side_lengths() -> None:
    fig = graph_plots.chain_graphs_figure(
        [FIG_4B, quad("Fig 2e", (18, 10, 17, 15))], title="Graphs", length_unit="cm"
    )
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    png, svg = figure_artifacts(fig, "chain_graphs", "Graphs")
    assert png_pixels(png.data).shape[2] in (3, 4)
    strings = svg_strings(svg.data)
    for text in (
        "Fig 4b",
        "Fig 2e",
        "a 6",
        "b 8",
        "c 9",
        "1",
        "2",
        "Graphs",
        "loop 3: peripheral (lengths outside)",
        "7 links, 8 joints, mobility 2",
    ):
        assert text in strings, text


def legend_texts(fig: Figure) -> list[str]:
    return [t.get_text() for legend in fig.legends for t in legend.get_texts()]


def test_chain_graphs_legend_names_the_vertex_kinds_drawn() -> None:
    fig = graph_plots.chain_graphs_figure([FIG_4B], title="Graphs", length_unit="cm")
    side = "next to a polygonal link: the length of the side (a, b, ...) the loop passes"
    assert legend_texts(fig) == ["binary link", "ternary link", "joint", "loop (numbered)",
                                 "side length used by a loop [cm]", side]  # fmt: skip
    single = graph_plots.chain_graphs_figure([quad("Fig 2e", (18, 10, 17, 15))], title="One")
    assert "ternary link" not in legend_texts(single) and side not in legend_texts(single)


def test_many_chains_wrap_into_rows() -> None:
    graphs = [quad(f"q{i}", (1.0 + i, 2.0, 3.0, 4.0)) for i in range(7)]
    fig = graph_plots.chain_graphs_figure(graphs, title="Seven")
    assert len(fig.axes) == 7
    assert len({round(ax.get_position().y0, 3) for ax in fig.axes}) == 3


def test_bars_label_values_and_ranks() -> None:
    fig = bars.parallelism_bars_figure(["A", "B", "C"], p_normalized=[0.0039, 0.0035, 0.0035],
                                    q=[0.0, 15650.0, 34592.0], title="Bars")  # fmt: skip
    strings = svg_strings(figure_artifacts(fig, "bars", "Bars")[1].data)
    for text in ("3.9   #1", "3.5   #2", "0   #1", "15.65   #2", "34.59   #3", "Bars"):
        assert text in strings, text
    # Values in thousandths and thousands: the power of ten is in the label, not the axis.
    assert [ax.get_xlabel() for ax in fig.axes] == [
        r"$P$ of $l / \sum l$ (eq 1) [$10^{-3}$]",
        r"$Q$ (eq 3) [$10^{3}$ units$^4$]",
    ]
    assert [ax.get_title() for ax in fig.axes] == [
        "normalised $P$  (larger: more uniform rigidity)",
        "$Q$  (smaller: more parallel)",
    ]
    assert fig.axes[0].get_ylabel() == "chain"
    assert legend_texts(fig) == ["best of the measure (rank #1; ties share a rank)",
                                 "other chains (value and rank #k on the bar)"]  # fmt: skip
    normalised = bars.parallelism_bars_figure(["A"], p_normalized=[0.1], q=[0.2], title="N",
                                           q_normalized=True)  # fmt: skip
    assert normalised.axes[1].get_xlabel() == r"$Q$ of $l / \sum l$ (eq 3) [-]"
    in_cm = bars.parallelism_bars_figure(["A"], p_normalized=[0.1], q=[0.2], title="C",
                                      length_unit="cm")  # fmt: skip
    assert in_cm.axes[1].get_xlabel() == "$Q$ (eq 3) [cm$^4$]"
    assert normalised.axes[1].get_title() == "$Q$ of normalised lengths  (smaller: more parallel)"


def test_fourbar_figure_renders() -> None:
    lengths = (18.0, 10.0, 17.0, 15.0)
    classified = classify_four_bar(lengths, 0)
    fig = fourbar.fourbar_figure(
        four_bar_poses(lengths, 0, np.linspace(0, 2 * np.pi, 181)), lengths=lengths,
        roles=classified.roles, full_turns=classified.full_turns, title="Four-bar",
        length_unit="cm",
    )  # fmt: skip
    strings = svg_strings(figure_artifacts(fig, "fourbar", "Four-bar")[1].data)
    for text in ("1: input 10", "0: ground 18", "full turn", "rocks", "x [cm]", "link that moves",
                 "link held fixed"):  # fmt: skip
        assert text in strings, text
    assert legend_texts(fig) == [
        "path of the input-coupler joint",
        "path of the coupler-output joint, assembly branch 1",
        "path of the coupler-output joint, assembly branch 2",
        "poses along branch 1",
        "ground pivots",
        "turns fully",
        "rocks (cannot turn fully)",
    ]


def test_fourbar_figure_of_a_chain_that_never_closes_at_theta_zero() -> None:
    lengths = (30.0, 17.0, 18.0, 25.0)
    classified = classify_four_bar(lengths, 0)
    poses = four_bar_poses(lengths, 0, np.linspace(0, 2 * np.pi, 91))
    assert np.isnan(poses[0, 45]).all()
    fourbar.fourbar_figure(poses, lengths=lengths, roles=classified.roles,
                     full_turns=classified.full_turns, title="Triple rocker")  # fmt: skip


@pytest.mark.parametrize(
    ("call", "parameter", "function"),
    [
        (lambda: graph_plots.chain_graphs_figure([], title="x"), "graphs", "chain_graphs_figure"),
        (lambda: graph_plots.chain_graphs_figure(
            [graph_plots.ChainGraph("x", ("1",), frozenset(), (), (("1",),), ((1.0, 2.0),))],
            title="x"),
         "graphs", "chain_graphs_figure"),
        (lambda: bars.parallelism_bars_figure(["a"], p_normalized=[1, 2], q=[1], title="x"),
         "p_normalized", "parallelism_bars_figure"),
        (lambda: bars.parallelism_bars_figure(["a"], p_normalized=[1], q=[math.nan], title="x"),
         "q", "parallelism_bars_figure"),
        (lambda: fourbar.fourbar_figure(np.zeros((2, 5, 3, 2)), lengths=(1, 1, 1, 1),
                                  roles=("ground", "input", "coupler", "output"),
                                  full_turns=np.zeros((4, 4), bool), title="x"),
         "poses", "fourbar_figure"),
    ],
)  # fmt: skip
def test_bad_parameters_name_the_parameter(call, parameter, function) -> None:
    with pytest.raises(ValueError, match=rf"The '{parameter}' parameter of {function} must be"):
        call()


def test_user_text_is_shown_literally() -> None:
    fig = bars.parallelism_bars_figure(["$a$"], p_normalized=[1.0], q=[1.0], title="$x$")
    assert "$x$" in svg_strings(figure_artifacts(fig, "t", "t")[1].data)
