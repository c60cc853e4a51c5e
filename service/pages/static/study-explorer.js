// A design study's explorer (study_explorer.html): sorting, filtering and paging fetch
// /v1/jobs/{jobID}/designs instead of reloading the page (the links and the form work
// without JavaScript); the scatter of two objectives is drawn with Plotly when it is
// loaded (else the PNG plots stand), and selecting a point shows its row, selecting a
// row's number marks its point.
"use strict";

(function () {
  const section = document.getElementById("designs");
  if (!section || !window.fetch) return;
  const table = document.getElementById("designs-table");
  const body = table.tBodies[0];
  const count = document.getElementById("designs-count");
  const actions = document.getElementById("design-actions");
  const jobId = section.dataset.job;
  const state = new URLSearchParams(window.location.search);
  for (const k of [...state.keys()]) {
    if (!["feasible", "pareto", "sort", "reason"].includes(k) || !state.get(k)) state.delete(k);
  }
  state.delete("cursor");
  let columns = [];

  function cell(tag, text, cls) {
    const el = document.createElement(tag);
    el.textContent = text;
    if (cls) el.className = cls;
    return el;
  }

  function number(value) {
    if (value === null || value === undefined) return "–";
    return Number(value.toPrecision(6)).toString();
  }

  function row(design) {
    const tr = document.createElement("tr");
    tr.id = "design-" + design.index;
    tr.dataset.index = design.index;
    if (!design.feasible) tr.className = "infeasible";
    const head = cell("th", String(design.index));
    head.scope = "row";
    if (design.pareto) {
      head.append(" ");
      head.append(cell("span", "★", "pareto-mark"));
    }
    tr.append(head);
    columns.forEach((c) => tr.append(cell("td", number(design.values[c.key]), "num")));
    const why = design.feasible ? "yes"
      : design.reason_code + (design.reason_field ? " (" + design.reason_field + ")" : "");
    tr.append(cell("td", why));
    const acts = actions.content.firstElementChild.cloneNode(true);
    acts.querySelector("form").action = "/pages/jobs/" + jobId + "/designs/" + design.index + "/run";
    acts.querySelector("a").href = "/pages/jobs/" + jobId + "/designs/" + design.index + "/edit";
    tr.append(acts);
    return tr;
  }

  function pager(next) {
    const nextLink = document.getElementById("designs-next");
    const holder = nextLink ? nextLink.parentElement : section.querySelector(".pager");
    holder.replaceChildren();
    if (state.get("cursor")) {
      const first = cell("a", "First page");
      first.href = "#designs";
      first.id = "designs-first";
      first.addEventListener("click", (e) => { e.preventDefault(); state.delete("cursor"); load(); });
      holder.append(first, " ");
    }
    if (next) {
      const more = cell("a", "Next designs");
      more.href = "#designs";
      more.id = "designs-next";
      more.rel = "next";
      more.addEventListener("click", (e) => {
        e.preventDefault();
        state.set("cursor", new URL(next, window.location.href).searchParams.get("cursor"));
        load();
      });
      holder.append(more);
    }
  }

  function headers() {
    const sort = state.get("sort") || "";
    table.querySelectorAll("thead a[data-sort]").forEach((a) => {
      const key = a.dataset.sort;
      const th = a.parentElement;
      if (sort === key) th.setAttribute("aria-sort", "ascending");
      else if (sort === "-" + key) th.setAttribute("aria-sort", "descending");
      else th.removeAttribute("aria-sort");
    });
  }

  async function load(selected) {
    const query = new URLSearchParams(state);
    query.set("limit", "25");
    section.setAttribute("aria-busy", "true");
    try {
      const answer = await fetch(section.dataset.src + "?" + query.toString(),
                                 { headers: { Accept: "application/json" } });
      const page = await answer.json();
      if (!answer.ok) {
        count.textContent = page.detail || "The designs could not be read.";
        return;
      }
      columns = page.columns;
      body.replaceChildren(...page.designs.map(row));
      count.textContent = page.matched.toLocaleString() + " of " + page.total.toLocaleString() +
        " designs" + (state.get("sort") ? ", sorted by " + state.get("sort") : ", feasible first") + ".";
      const next = page.links.find((l) => l.rel === "next");
      pager(next ? next.href : null);
      headers();
      const shown = new URLSearchParams(state);
      shown.delete("cursor");
      shown.delete("range");
      window.history.replaceState(null, "", "?" + shown.toString() + "#designs");
      if (selected !== undefined) {
        const tr = document.getElementById("design-" + selected);
        if (tr) { tr.classList.add("selected"); tr.scrollIntoView({ block: "nearest" }); }
      }
      section.dataset.loaded = String(Date.now());
    } finally {
      section.removeAttribute("aria-busy");
    }
  }

  table.querySelectorAll("thead a[data-sort]").forEach((a) => {
    a.addEventListener("click", (e) => {
      e.preventDefault();
      const key = a.dataset.sort;
      state.set("sort", state.get("sort") === key ? "-" + key : key);
      state.delete("cursor");
      state.delete("range");
      load();
    });
  });
  const filters = document.getElementById("design-filters");
  filters.addEventListener("submit", (e) => {
    e.preventDefault();
    ["feasible", "pareto", "reason"].forEach((k) => {
      const v = filters.elements[k] ? filters.elements[k].value : "";
      if (v) state.set(k, v); else state.delete(k);
    });
    state.delete("cursor");
    state.delete("range");
    load();
  });
  filters.querySelectorAll("select").forEach((s) =>
    s.addEventListener("change", () => filters.requestSubmit()));
  const firstNext = document.getElementById("designs-next");
  if (firstNext) {
    firstNext.addEventListener("click", (e) => {
      e.preventDefault();
      state.set("cursor", new URL(firstNext.href).searchParams.get("cursor"));
      load();
    });
  }

  // The scatter: every design (or, beyond 10,000, their density) and the front.
  const chart = document.getElementById("study-scatter");
  function showDesign(index) {
    state.set("range", "index:" + index + ":" + index);
    state.delete("cursor");
    load(index).then(() => {
      const back = cell("a", "All designs");
      back.href = "#designs";
      back.id = "designs-all";
      back.addEventListener("click", (e) => { e.preventDefault(); state.delete("range"); load(); });
      section.querySelector(".pager").append(" ", back);
    });
  }
  async function drawScatter() {
    if (!chart || !window.Plotly) return;
    const answer = await fetch(chart.dataset.src, { headers: { Accept: "application/json" } });
    if (!answer.ok) return;
    const data = await answer.json();
    const label = (key) => {
      const c = columns.find((col) => col.key === key);
      return c ? c.label : key;
    };
    const traces = [];
    if (data.bins) {
      const mid = (e) => e.slice(0, -1).map((v, i) => (v + e[i + 1]) / 2);
      const z = data.bins.y_edges.slice(0, -1).map((_, j) => data.bins.counts.map((col) => col[j] || null));
      traces.push({ type: "heatmap", x: mid(data.bins.x_edges), y: mid(data.bins.y_edges), z: z,
        colorscale: "Greys", reversescale: true, name: "designs per bin",
        colorbar: { title: { text: "designs" } }, hovertemplate: "%{z} designs<extra></extra>" });
    }
    const pts = data.points;
    const front = pts.index.map((_, i) => i).filter((i) => pts.pareto[i]);
    const rest = pts.index.map((_, i) => i).filter((i) => !pts.pareto[i]);
    const trace = (which, name, color, size) => ({
      type: "scatter", mode: "markers", name: name,
      x: which.map((i) => pts.x[i]), y: which.map((i) => pts.y[i]),
      customdata: which.map((i) => pts.index[i]),
      marker: { color: color, size: size },
      hovertemplate: "design %{customdata}<br>" + label(data.x) + " = %{x}<br>" +
        label(data.y) + " = %{y}<extra>" + name + "</extra>",
    });
    if (rest.length) traces.push(trace(rest, "designs", "#8d96a0", 5));
    if (front.length) traces.push(trace(front, "non-dominated", "#b35900", 8));
    const layout = { margin: { t: 20, r: 20 }, xaxis: { title: { text: label(data.x) } },
      yaxis: { title: { text: label(data.y) } }, hovermode: "closest",
      legend: { orientation: "h", y: -0.2 } };
    await window.Plotly.newPlot(chart, traces, layout, { responsive: true, displaylogo: false });
    chart.on("plotly_click", (event) => {
      const point = event.points && event.points[0];
      if (point && point.customdata !== undefined) showDesign(point.customdata);
    });
    chart.dataset.drawn = "true";
  }
  body.addEventListener("click", (e) => {
    const th = e.target.closest("th[scope=row]");
    if (!th || !chart || chart.dataset.drawn !== "true") return;
    const index = Number(th.parentElement.dataset.index);
    body.querySelectorAll("tr.selected").forEach((tr) => tr.classList.remove("selected"));
    th.parentElement.classList.add("selected");
    window.Plotly.Fx.hover(chart, chart.data.flatMap((t, curve) =>
      (t.customdata || []).map((d, pointNumber) => ({ curveNumber: curve, pointNumber, d })))
      .filter((p) => p.d === index).map(({ curveNumber, pointNumber }) => ({ curveNumber, pointNumber })));
  });
  load().then(drawScatter);
})();
