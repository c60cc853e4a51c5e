// Live progress of a job page: follows GET /v1/jobs/{id}/events (Server-Sent Events)
// and reloads the page once the job has ended, to show its results.  While it runs, the
// duration counts up and the time left is estimated from the progress, as the server
// does: elapsed * (100 - p) / p.
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
  var duration = document.getElementById("job-duration");
  var eta = document.getElementById("job-eta");
  var started = duration && duration.dataset.started ? Date.parse(duration.dataset.started) : NaN;
  var source = new EventSource(section.dataset.events);

  function spoken(seconds) {
    if (seconds < 10) {
      return seconds.toFixed(1) + " s";
    }
    var whole = Math.round(seconds);
    if (whole < 60) {
      return whole + " s";
    }
    var minutes = Math.floor(whole / 60);
    var secs = String(whole % 60).padStart(2, "0");
    if (minutes < 60) {
      return minutes + " min " + secs + " s";
    }
    return Math.floor(minutes / 60) + " h " + String(minutes % 60).padStart(2, "0") + " min";
  }

  function elapsed() {
    return isNaN(started) ? NaN : Math.max(0, (Date.now() - started) / 1000);
  }

  function tick() {
    var seconds = elapsed();
    if (duration && !isNaN(seconds)) {
      duration.textContent = spoken(seconds) + " so far";
    }
  }

  function estimate(state) {
    var seconds = elapsed();
    if (!eta) {
      return;
    }
    if (state.status === "running" && state.progress > 0 && state.progress < 100 && !isNaN(seconds)) {
      eta.textContent = "about " + spoken((seconds * (100 - state.progress)) / state.progress);
    }
  }

  var ticking = window.setInterval(tick, 1000);

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
    if (state.status === "running" && isNaN(started) && duration === null) {
      started = Date.now(); // it started after the page was drawn
    }
    estimate(state);
    if (terminal[state.status]) {
      window.clearInterval(ticking);
      source.close();
      window.location.reload();
    }
  });
})();
