// A listing that keeps itself current (the jobs list, the queue): while the tab is
// visible it asks for this same page every few seconds and swaps in the new content of
// the element marked data-refresh-seconds (statuses, progress, durations).  Without
// JavaScript the jobs list reloads itself while a listed job is queued or running.
(function () {
  "use strict";
  var listing = document.querySelector("[data-refresh-seconds][id]");
  if (!listing || !window.fetch || !window.DOMParser) {
    return;
  }
  var seconds = Number(listing.dataset.refreshSeconds) || 5;
  var busy = false;

  function refresh() {
    if (busy || document.visibilityState === "hidden") {
      return;
    }
    busy = true;
    fetch(window.location.href, { headers: { Accept: "text/html" }, credentials: "same-origin" })
      .then(function (response) {
        return response.ok ? response.text() : null;
      })
      .then(function (html) {
        if (!html) {
          return;
        }
        var fresh = new DOMParser().parseFromString(html, "text/html").getElementById(listing.id);
        if (fresh && fresh.innerHTML !== listing.innerHTML) {
          var adopted = document.importNode(fresh, true);
          // keep what the user ticked (the jobs to compare)
          listing.querySelectorAll("input[type=checkbox]:checked").forEach(function (box) {
            adopted.querySelectorAll("input[type=checkbox]").forEach(function (other) {
              if (other.name === box.name && other.value === box.value) {
                other.checked = true;
              }
            });
          });
          listing.replaceWith(adopted);
          listing = adopted;
        }
        listing.dataset.refreshedAt = new Date().toISOString();
      })
      .catch(function () {})
      .then(function () {
        busy = false;
      });
  }

  window.setInterval(refresh, seconds * 1000);
})();
