// The live map: draws /references/NAME/map.json with Cytoscape.js, redraws on every
// server-sent event of /references/NAME/events, explains a location on click.
"use strict";
(function () {
  const name = decodeURIComponent(location.pathname.split("/")[2]);
  const base = "/references/" + encodeURIComponent(name);
  const state = { events: 0, last: null };
  document.getElementById("reference").textContent = name;

  const cy = cytoscape({
    container: document.getElementById("graph"),
    wheelSensitivity: 0.3,
    style: [
      { selector: "node", style: { "label": "data(id)", "font-size": 11, "text-valign": "center",
                                   "text-halign": "center", "border-width": 1, "border-color": "#666" } },
      { selector: "node.ROOM, node.LOCATION", style: { "shape": "round-rectangle", "background-color": "#90caf9",
                                                         "width": 46, "height": 30 } },
      { selector: "node.CORRIDOR", style: { "shape": "round-rectangle", "background-color": "#ffe082",
                                            "width": 70, "height": 30 } },
      { selector: "node.urgent", style: { "background-color": "#ef5350", "border-width": 3,
                                          "border-color": "#b71c1c", "color": "#fff" } },
      { selector: "node.door", style: { "shape": "diamond", "background-color": "#bdbdbd", "width": 16,
                                        "height": 16, "font-size": 8, "text-valign": "bottom" } },
      { selector: "node.robot", style: { "shape": "triangle", "background-color": "#a5d6a7", "width": 30,
                                         "height": 30, "text-valign": "bottom", "text-margin-y": 4 } },
      { selector: "node.selected", style: { "border-width": 4, "border-color": "#1565c0" } },
      { selector: "edge", style: { "width": 2, "line-color": "#999", "curve-style": "bezier" } },
      { selector: "edge.isIn", style: { "line-style": "dashed", "line-color": "#43a047",
                                        "target-arrow-shape": "triangle", "target-arrow-color": "#43a047" } },
    ],
  });

  function elements(map) {
    const els = [];
    map.locations.forEach(l => els.push({ group: "nodes", data: { id: l.id, kind: l.kind },
                                          classes: [l.kind, l.urgent ? "urgent" : "", "location"].join(" ") }));
    map.doors.forEach(d => els.push({ group: "nodes", data: { id: d.id }, classes: "door" }));
    map.robots.forEach(r => els.push({ group: "nodes", data: { id: r.id }, classes: "robot" }));
    map.links.forEach(k => els.push({ group: "edges", data: { id: k.kind + ":" + k.source + "->" + k.target,
                                                             source: k.source, target: k.target }, classes: k.kind }));
    // an edge is drawn only between drawn nodes (a door that is not a DOOR, e.g. while inconsistent, is not)
    const ids = new Set(els.filter(e => e.group === "nodes").map(e => e.data.id));
    return els.filter(e => e.group === "nodes" || (ids.has(e.data.source) && ids.has(e.data.target)));
  }

  function sameShape(els) {
    const want = new Set(els.map(e => e.data.id));
    if (want.size !== cy.elements().length) return false;
    return cy.elements().every(e => want.has(e.id()));
  }

  function render(map) {
    const els = elements(map);
    if (sameShape(els)) {
      els.forEach(e => { if (e.group === "nodes") cy.getElementById(e.data.id).classes(e.classes +
        (cy.getElementById(e.data.id).hasClass("selected") ? " selected" : "")); });
    } else {
      cy.elements().remove();
      cy.add(els);
      cy.layout({ name: "cose", animate: false, randomize: false, nodeRepulsion: 9000, idealEdgeLength: 50 }).run();
    }
    const list = document.getElementById("urgent");
    list.replaceChildren(...map.urgent.map(u => { const li = document.createElement("li"); li.textContent = u; return li; }));
    const status = document.getElementById("status");
    status.className = map.consistent === false ? "inconsistent" : "";
    status.textContent = (map.consistent === false ? "INCONSISTENT" : "consistent") +
      " · " + map.locations.length + " locations · events received: " + state.events;
    document.body.dataset.events = String(state.events);
  }

  async function refresh() {
    const res = await fetch(base + "/map.json", { cache: "no-store" });
    if (res.ok) render(await res.json());
  }

  function logEvent(ev) {
    const li = document.createElement("li");
    const parts = [`#${ev.seq}`];
    ev.added.forEach(t => parts.push(`<span class="added">+ ${esc(t.s)} ${esc(t.p)} ${esc(t.o)}</span>`));
    ev.removed.forEach(t => parts.push(`<span class="removed">− ${esc(t.s)} ${esc(t.p)} ${esc(t.o)}</span>`));
    if (ev.missed) parts.push(`(${ev.missed} events missed)`);
    if (ev.consistency_changed) parts.push(ev.consistent ? "now consistent" : "now INCONSISTENT");
    li.innerHTML = parts.join(" ");
    const log = document.getElementById("log");
    log.prepend(li);
    while (log.children.length > 50) log.lastChild.remove();
  }

  function esc(s) {
    return String(s).replace(/[&<>"']/g, c => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" }[c]));
  }

  function tree(node) {
    const li = document.createElement("li");
    if (node.status === "inferred") {
      li.innerHTML = `${esc(node.triple)} <span class="rule">← ${esc(node.rule)}: ${esc(node.origin)}</span>`;
      const ul = document.createElement("ul");
      (node.premises || []).forEach(p => ul.appendChild(tree(p)));
      li.appendChild(ul);
    } else {
      li.innerHTML = `${esc(node.triple)} <span class="${node.status.replace(" ", "")}">[${esc(node.status)}]</span>`;
    }
    return li;
  }

  async function explain(node) {
    cy.nodes().removeClass("selected");
    node.addClass("selected");
    const cls = node.hasClass("urgent") ? "URGENT" : node.data("kind");
    const q = new URLSearchParams({ s: node.id(), p: "rdf:type", o: cls });
    const res = await fetch(base + "/explain?" + q.toString(), { cache: "no-store" });
    const box = document.getElementById("explanation");
    const body = await res.json();
    const ul = document.createElement("ul");
    if (res.ok) ul.appendChild(tree(body)); else ul.textContent = body.error;
    const more = document.createElement("a");
    more.href = "inspector#entity/" + encodeURIComponent(node.id());
    more.textContent = "all of " + node.id() + " in the inspector";
    box.replaceChildren(ul, more);
  }

  cy.on("tap", "node.location", evt => explain(evt.target));

  const source = new EventSource(base + "/events");
  source.addEventListener("reason", msg => {
    state.events += 1;
    const ev = JSON.parse(msg.data);
    logEvent(ev);
    refresh();
  });
  source.onopen = () => refresh();
  refresh();
  window.topostoreMap = { cy, refresh };
})();
