// The live explorer (service/pages/explorer.py): each change of a design field posts
// the inputs to the process's preview (a newer change aborts the older request) and
// redraws the heat maps (Plotly) and the indices.  When a preview is drawn the
// explorer's data-drawn attribute holds the number of the change it shows (the
// latency bench and the browser tests wait on it) and an "explorer:drawn" event fires.
(function () {
  "use strict";
  var root = document.getElementById("explorer");
  var configNode = document.getElementById("explorer-config");
  if (!root || !configNode || !window.Plotly) {
    return;
  }
  var config = JSON.parse(configNode.textContent);
  var inputs = JSON.parse(JSON.stringify(config.inputs));
  var status = document.getElementById("explorer-status");
  var charts = document.getElementById("explorer-charts");
  var indexBody = document.querySelector("#explorer-indices tbody");
  var notesList = document.getElementById("explorer-notes");
  var runForm = document.getElementById("explorer-run");
  var csrfInput = runForm ? runForm.querySelector("input[name=csrf_token]") : null;
  var controller = null;
  var changes = 0;

  function setPath(target, path, value) {
    var parts = path.split(".");
    var node = target;
    for (var i = 0; i < parts.length - 1; i++) {
      node = node[parts[i]];
    }
    node[parts[parts.length - 1]] = value;
  }

  function withUnit(label, unit) {
    return unit ? label + " [" + unit + "]" : label;
  }

  function hoverText(map) {
    function part(label, key, unit) {
      return label + " = %{" + key + ":.4~g}" + (unit ? " " + unit : "");
    }
    return part(map.x_label, "x", map.x_unit) + "<br>" + part(map.y_label, "y", map.y_unit) +
      "<br>" + part(map.z_label, "z", map.z_unit) + "<extra></extra>";
  }

  function chartDiv(index) {
    var div = charts.children[index];
    if (!div) {
      div = document.createElement("div");
      div.className = "explorer-chart";
      charts.appendChild(div);
    }
    return div;
  }

  // Maps of one quantity over the same axes (the SPM's panels at several torsions) are
  // drawn as one figure of stacked panels sharing a colour bar: one layout and one
  // redraw instead of one per panel.
  function groups(maps) {
    var byKey = {};
    var list = [];
    maps.forEach(function (map) {
      var key = [map.x_label, map.x_unit, map.y_label, map.y_unit, map.z_label, map.z_unit]
        .join("|");
      if (!byKey[key]) {
        byKey[key] = [];
        list.push(byKey[key]);
      }
      byKey[key].push(map);
    });
    return list;
  }

  function drawGroup(maps, index) {
    var first = maps[0];
    var square = first.x_unit === first.y_unit && first.x_unit !== "deg";
    var layout = {
      margin: {l: 60, r: 20, t: 30, b: 50},
      coloraxis: {colorscale: "Viridis",
                  colorbar: {title: {text: withUnit(first.z_label, first.z_unit)}}},
      annotations: [],
      uirevision: config.process_id
    };
    var traces = maps.map(function (map, k) {
      var suffix = k === 0 ? "" : String(k + 1);
      var domain = [1 - (k + 1) / maps.length + 0.06, 1 - k / maps.length - 0.04];
      if (maps.length === 1) {
        domain = [0, 1];
      }
      layout["xaxis" + suffix] = {anchor: "y" + suffix, title: {text: k === maps.length - 1 ?
        withUnit(map.x_label, map.x_unit) : ""}};
      layout["yaxis" + suffix] = {anchor: "x" + suffix, domain: domain,
                                  title: {text: withUnit(map.y_label, map.y_unit)}};
      if (square) {
        layout["yaxis" + suffix].scaleanchor = "x" + suffix;
      }
      layout.annotations.push({text: map.title, showarrow: false, xref: "paper",
                               yref: "paper", x: 0, xanchor: "left", y: domain[1],
                               yanchor: "bottom", font: {size: 13}});
      return {type: "heatmap", x: map.x, y: map.y, z: map.z, coloraxis: "coloraxis",
              xaxis: "x" + suffix, yaxis: "y" + suffix, hoverongaps: false,
              hovertemplate: hoverText(map)};
    });
    var div = chartDiv(index);
    div.classList.toggle("explorer-chart-tall", maps.length > 1);
    return window.Plotly.react(div, traces, layout, {
      responsive: true, displaylogo: false,
      toImageButtonOptions: {format: "png", filename: config.process_id}
    });
  }

  function showNumber(value) {
    if (value === null || value === undefined) {
      return "—";
    }
    return Number.isInteger(value) ? String(value) : Number(value).toPrecision(5);
  }

  function drawIndices(indices, notes) {
    indexBody.textContent = "";
    indices.forEach(function (index) {
      var row = document.createElement("tr");
      var name = document.createElement("th");
      name.scope = "row";
      name.textContent = index.label;
      var cell = document.createElement("td");
      cell.textContent = showNumber(index.value) + (index.unit ? " " + index.unit : "");
      cell.dataset.name = index.name;
      row.appendChild(name);
      row.appendChild(cell);
      indexBody.appendChild(row);
    });
    notesList.textContent = "";
    notes.forEach(function (note) {
      var item = document.createElement("li");
      item.textContent = note;
      notesList.appendChild(item);
    });
  }

  function draw(doc, change) {
    var figures = groups(doc.maps);
    while (charts.children.length > figures.length) {
      window.Plotly.purge(charts.lastChild);
      charts.removeChild(charts.lastChild);
    }
    drawIndices(doc.indices, doc.notes || []);
    return Promise.all(figures.map(drawGroup)).then(function () {
      root.dataset.state = "drawn";
      root.dataset.drawn = String(change);
      status.textContent = "Cost " + doc.cost.toLocaleString() + " " + doc.cost_unit + ".";
      root.dispatchEvent(new CustomEvent("explorer:drawn", {detail: {change: change}}));
    });
  }

  function refused(problem, change) {
    root.dataset.state = "refused";
    root.dataset.drawn = String(change);
    status.textContent = problem.detail || problem.title || "The preview was refused.";
    root.dispatchEvent(new CustomEvent("explorer:drawn", {detail: {change: change}}));
  }

  function preview() {
    changes += 1;
    var change = changes;
    if (controller) {
      controller.abort();
    }
    controller = new AbortController();
    var headers = {"Content-Type": "application/json", "Accept": "application/json"};
    if (csrfInput) {
      headers[config.csrf_header] = csrfInput.value;
    }
    root.dataset.state = "loading";
    fetch(config.preview_url, {
      method: "POST", headers: headers, body: JSON.stringify({inputs: inputs}),
      signal: controller.signal, credentials: "same-origin"
    }).then(function (response) {
      return response.json().then(function (body) {
        if (change !== changes) {
          return null;
        }
        return response.ok ? draw(body, change) : refused(body, change);
      });
    }).catch(function (error) {
      if (error.name !== "AbortError") {
        status.textContent = "The preview failed: " + error.message;
      }
    });
  }

  function onInput(event) {
    var field = event.target;
    var value = parseFloat(field.value);
    if (!isFinite(value)) {
      return;
    }
    document.querySelectorAll("#explorer-fields input[data-path='" + field.dataset.path + "']")
      .forEach(function (other) {
        if (other !== field) {
          other.value = field.value;
        }
      });
    setPath(inputs, field.dataset.path, value);
    preview();
  }

  function jobInputs() {
    var copy = JSON.parse(JSON.stringify(inputs));
    // a job takes the worked example's resolution and plots, not the explorer's
    Object.keys(config.job_restores || {}).forEach(function (key) {
      var value = config.job_restores[key];
      if (value === null || value === undefined) {
        delete copy[key];
      } else {
        copy[key] = value;
      }
    });
    return JSON.stringify(copy, null, 2);
  }

  var compareKey = "dexlab-compare-" + config.process_id;
  var compareLink = document.getElementById("explorer-compare-link");

  function comparedJobs() {
    try {
      return JSON.parse(window.sessionStorage.getItem(compareKey) || "[]");
    } catch (error) {
      return [];
    }
  }

  function showCompareLink() {
    var jobs = comparedJobs();
    compareLink.hidden = jobs.length === 0;
    compareLink.href = "/pages/compare?" + jobs.map(function (id) {
      return "jobs=" + encodeURIComponent(id);
    }).join("&");
    compareLink.textContent = jobs.length < 2 ? "Compare (add one more design)" :
      "Compare " + jobs.length + " designs";
  }

  function addToComparison() {
    var body = new URLSearchParams();
    if (csrfInput) {
      body.set("csrf_token", csrfInput.value);
    }
    body.set("inputs", jobInputs());
    status.textContent = "Submitting this design as a job…";
    fetch(runForm.action, {method: "POST", body: body, credentials: "same-origin"})
      .then(function (response) {
        var match = /\/v1\/jobs\/([^/?#]+)/.exec(response.url);
        if (!response.ok || !match) {
          status.textContent = "The design could not be submitted (HTTP " + response.status + ").";
          return;
        }
        var jobs = comparedJobs().filter(function (id) { return id !== match[1]; });
        jobs.push(match[1]);
        window.sessionStorage.setItem(compareKey, JSON.stringify(jobs.slice(-6)));
        showCompareLink();
        status.textContent = "Added job " + match[1].slice(0, 8) + " to the comparison.";
      });
  }

  document.querySelectorAll("#explorer-fields input").forEach(function (field) {
    field.addEventListener("input", onInput);
  });
  document.getElementById("explorer-fields").addEventListener("submit", function (event) {
    event.preventDefault();
  });
  runForm.addEventListener("submit", function () {
    document.getElementById("explorer-run-inputs").value = jobInputs();
  });
  document.getElementById("explorer-compare-add").addEventListener("click", addToComparison);
  showCompareLink();
  preview();
})();
