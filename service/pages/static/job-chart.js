// A finished map job's interactive heat map (service/pages/data_charts.py), drawn with
// Plotly from the job's own CSV (one row per grid node, columns "quantity [unit]");
// the PNG plots stay below it.  When drawn, the chart's data-drawn attribute is set.
(function () {
  "use strict";
  var chart = document.getElementById("job-chart");
  if (!chart || !window.Plotly) {
    return;
  }
  var data = chart.dataset;

  function columnOf(header, quantity) {
    for (var i = 0; i < header.length; i++) {
      var match = /^(.*) \[(.*)\]$/.exec(header[i].trim());
      if (match && match[1] === quantity) {
        return {index: i, unit: match[2] === "-" ? "" : match[2]};
      }
    }
    throw new Error("the data file has no column " + quantity);
  }

  function grid(text) {
    var lines = text.split(/\r?\n/).filter(function (line) {
      return line && line.charAt(0) !== "#";
    });
    var header = lines[0].split(",");
    var cx = columnOf(header, data.x), cy = columnOf(header, data.y), cz = columnOf(header, data.z);
    var blank = data.blankAtOrBelow === undefined ? null : parseFloat(data.blankAtOrBelow);
    var xs = [], ys = [], xIndex = new Map(), yIndex = new Map(), cells = [];
    for (var i = 1; i < lines.length; i++) {
      var cols = lines[i].split(",");
      var x = cols[cx.index], y = cols[cy.index], z = parseFloat(cols[cz.index]);
      if (!xIndex.has(x)) { xIndex.set(x, xs.length); xs.push(parseFloat(x)); }
      if (!yIndex.has(y)) { yIndex.set(y, ys.length); ys.push(parseFloat(y)); }
      cells.push([yIndex.get(y), xIndex.get(x), isFinite(z) && (blank === null || z > blank) ? z : null]);
    }
    var z = ys.map(function () { return new Array(xs.length).fill(null); });
    cells.forEach(function (cell) { z[cell[0]][cell[1]] = cell[2]; });
    return {x: xs, y: ys, z: z, units: [cx.unit, cy.unit, cz.unit]};
  }

  function label(name, unit) {
    return unit ? name + " [" + unit + "]" : name;
  }

  function part(name, key, unit) {
    return name + " = %{" + key + ":.4~g}" + (unit ? " " + unit : "");
  }

  fetch(data.csv, {credentials: "same-origin"}).then(function (response) {
    if (!response.ok) {
      throw new Error("HTTP " + response.status);
    }
    return response.text();
  }).then(function (text) {
    var map = grid(text);
    var units = map.units;
    chart.hidden = false;
    var square = units[0] === units[1];
    return window.Plotly.newPlot(chart, [{
      type: "heatmap", x: map.x, y: map.y, z: map.z, colorscale: "Viridis", hoverongaps: false,
      colorbar: {title: {text: label(data.z, units[2])}},
      hovertemplate: part(data.x, "x", units[0]) + "<br>" + part(data.y, "y", units[1]) +
        "<br>" + part(data.z, "z", units[2]) + "<extra></extra>"
    }], {
      title: {text: data.title + " (interactive)", font: {size: 14}},
      margin: {l: 60, r: 20, t: 40, b: 50},
      xaxis: {title: {text: label(data.x, units[0])}},
      yaxis: {title: {text: label(data.y, units[1])}, scaleanchor: square ? "x" : undefined}
    }, {responsive: true, displaylogo: false});
  }).then(function () {
    chart.dataset.drawn = "1";
  }).catch(function (error) {
    chart.hidden = true;  // the PNG plots below remain
    chart.dataset.failed = error.message;
  });
})();
