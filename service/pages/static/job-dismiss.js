// Dismissing a job from its page: with JavaScript, a dialog asks first and the hidden
// form posts the dismissal; without it, the button opens a page that asks.
(function () {
  "use strict";
  var ask = document.getElementById("dismiss-ask");
  var post = document.getElementById("dismiss-post");
  if (!ask || !post) {
    return;
  }
  ask.addEventListener("submit", function (event) {
    event.preventDefault();
    if (window.confirm(ask.dataset.question || "Dismiss this job?")) {
      post.submit();
    }
  });
})();
