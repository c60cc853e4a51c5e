// Live progress of a job page: follows GET /v1/jobs/{id}/events (Server-Sent Events)
// and reloads the page once the job has ended, to show its results.
(function () {
  "use strict";
  var section = document.getElementById("job-status");
  if (!section || !section.dataset.events || !window.EventSource) {
    return;
  }
  var terminal = { successful: true, failed: true, dismissed: true };
  var bar = document.getElementById("job-progress");
  var text = document.getElementById("job-progress-text");
  var message = document.getElementById("job-message");
  var badge = document.querySelector("#job-status-value .badge");
  var source = new EventSource(section.dataset.events);

  source.addEventListener("progress", function (event) {
    var state;
    try {
      state = JSON.parse(event.data);
    } catch (err) {
      return;
    }
    bar.value = state.progress;
    bar.textContent = state.progress + "%";
    text.textContent = state.progress + "%";
    message.textContent = state.message || "";
    if (badge) {
      badge.textContent = state.status;
      badge.className = "badge status-" + state.status;
    }
    section.dataset.status = state.status;
    if (terminal[state.status]) {
      source.close();
      window.location.reload();
    }
  });
})();
