// The inspector page: entity pages (/entities/{entity}), search, the SPARQL console (YASGUI, vendored),
// the consistency report and the history, one view at a time (#entity/R1, #sparql, #history, #consistency).
// Every view is redrawn after each REASON (server-sent events of /events).
"use strict";
(function () {
  const R = window.InspectorRender;
  const h = R.h;
  const name = decodeURIComponent(location.pathname.split("/")[2]);
  const base = "/references/" + encodeURIComponent(name);
  const state = { events: 0, yasgui: null, queries: null };
  document.getElementById("reference").textContent = name;
  document.getElementById("maplink").href = base + "/map";

  async function getJson(path) {
    const res = await fetch(base + path, { cache: "no-store" });
    const body = await res.json();
    if (!res.ok) throw new Error(body.error || res.statusText);
    return body;
  }

  // the view the address asks for now ("entity/R1", "sparql", "history", "consistency" or "overview")
  function asked() {
    const hash = decodeURIComponent(location.hash.replace(/^#/, ""));
    if (hash.startsWith("entity/")) return hash;
    return ["sparql", "history", "consistency"].includes(hash) ? hash : "overview";
  }

  // a view drawn for an earlier address (a redraw still fetching when the user went elsewhere) is
  // dropped: whichever fetch ends last, the view shown is the one the address asks for
  function show(id, ...content) {
    const want = asked();
    if (want !== id && !(id === "entity" && want.startsWith("entity/"))) return;
    document.querySelectorAll("section.view").forEach(s => { s.hidden = s.id !== id; });
    document.querySelectorAll("header nav a[data-view]").forEach(a =>
      a.classList.toggle("active", a.dataset.view === id));
    if (content.length) document.getElementById(id).replaceChildren(...content);
  }

  function failure(id, err) { show(id, h("div", { class: "warning" }, String(err.message || err))); }

  // ------------------------------------------------------------------ the status badge
  function showStatus(consistent) {
    const el = document.getElementById("status");
    el.className = consistent === false ? "inconsistent" : (consistent === null ? "unknown" : "");
    el.textContent = consistent === false ? "INCONSISTENT" : (consistent === null ? "not reasoned" : "consistent");
    document.body.dataset.consistent = String(consistent);
  }

  // ------------------------------------------------------------------ entity pages
  const value = f => R.term(f.value);
  const SECTIONS = [
    ["types", "Types", [{ title: "class", cell: f => R.term(f.class) }]],
    ["values", "Property values", [{ title: "property", cell: f => R.term(f.property) }, { title: "value", cell: value }]],
    ["referenced_by", "Referenced by", [{ title: "subject", cell: f => R.term(f.subject) },
                                        { title: "property", cell: f => R.term(f.property) }]],
    ["different_from", "Different individuals", [{ title: "individual", cell: f => R.term(f.individual) },
                                                 { title: "axiom", cell: f => h("span", { class: "mono" }, f.axiom) }]],
    ["superclasses", "Superclasses", [{ title: "class", cell: f => R.term(f.class) }]],
    ["subclasses", "Subclasses", [{ title: "class", cell: f => R.term(f.class) }]],
    ["members", "Members", [{ title: "individual", cell: f => R.term(f.individual) }]],
    ["assertions", "Assertions", [{ title: "subject", cell: f => R.term(f.subject) }, { title: "value", cell: value }]],
  ];

  function propertyBox(e) {
    const rows = [["characteristics", (e.characteristics || []).join(", ")], ["domain", (e.domain || []).join(", ")],
                  ["range", (e.range || []).join(", ")]];
    const list = h("ul", {}, rows.filter(r => r[1]).map(r => h("li", {}, r[0] + ": ", R.linked(r[1], e.links))));
    (e.superproperties || []).forEach(t => list.append(h("li", {}, "sub-property of ", R.term(t))));
    (e.inverse_of || []).forEach(t => list.append(h("li", {}, "inverse of ", R.term(t))));
    return list.children.length ? h("div", { class: "card" }, list) : "";
  }

  function entityPage(e) {
    const parts = [h("h1", {}, e.name, e.kinds.map(k => h("span", { class: "kindtag" }, k))),
                   h("div", { class: "iri" }, e.iri), R.legend(), ...R.warnings(e.warnings)];
    (e.annotations || []).forEach(a => parts.push(h("p", {}, R.term(a.value))));
    if (e.kinds.some(k => k.endsWith("property"))) parts.push(propertyBox(e));
    SECTIONS.forEach(([key, title, columns]) => {
      const facts = e[key];
      if (facts === undefined || (!facts.length && !e.kinds.includes("individual"))) return;
      const count = e.truncated && e.truncated[key] ? ` (${facts.length} of ${e.truncated[key]})` : "";
      parts.push(h("h2", {}, title + count), R.factTable(facts, columns, e.links));
    });
    if ((e.axioms || []).length) {
      parts.push(h("h2", {}, "Axioms"), h("div", { class: "card" },
        h("ul", {}, e.axioms.map(a => h("li", { class: "mono" }, R.linked(a.text, e.links))))));
    }
    if ((e.rules || []).length) {
      parts.push(h("h2", {}, "SWRL rules"), h("div", { class: "card" }, h("ul", {}, e.rules.map(r =>
        h("li", {}, h("b", {}, r.name + " "), h("span", { class: "mono" }, R.linked(r.text, e.links)))))));
    }
    return parts;
  }

  async function showEntity(entity) {
    try {
      const e = await getJson("/entities/" + encodeURIComponent(entity));
      if (asked() !== "entity/" + entity) return;  // another entity or view was asked for meanwhile
      show("entity", ...entityPage(e));
      document.title = "topostore — " + e.name;
      document.getElementById("entity").dataset.iri = e.iri;
    } catch (err) { failure("entity", err); }
  }

  // ------------------------------------------------------------------ overview and search
  async function showOverview() {
    try {
      const [found, report] = await Promise.all([getJson("/entities?limit=5000"), getJson("/consistency?brief=true")]);
      const groups = {};
      found.entities.forEach(e => (groups[e.kind] = groups[e.kind] || []).push(e));
      const order = ["class", "object property", "data property", "annotation property", "individual"];
      const cards = order.filter(k => groups[k]).map(k => h("div", { class: "card" }, h("h2", {}, k.replace("class", "classes")
        .replace("property", "properties").replace("individual", "individuals") + ` (${groups[k].length})`),
        h("ul", {}, groups[k].map(e => h("li", {}, R.entityLink(e.name))))));
      const cut = found.total > found.entities.length
        ? h("div", { class: "warning" }, `The first ${found.entities.length} of ${found.total} entities are listed; ` +
            "use the search box for the others.") : "";
      show("overview", h("h1", {}, "Reference " + name), consistencySummary(report), cut,
           h("p", { class: "hint" }, "Pick an entity to see its facts: asserted ones in green, inferred ones in yellow, " +
             "each inferred fact with the proof that derives it."), h("div", { class: "grid" }, cards));
    } catch (err) { failure("overview", err); }
  }

  function consistencySummary(report) {
    if (report.consistent === false) {
      return h("div", { class: "card violation" }, h("span", { class: "message" },
        `Inconsistent: ${report.violation_count ?? report.violations.length} violation(s). `), h("a", { href: "#consistency" }, "See which axiom and which individuals"));
    }
    return h("div", { class: "card" }, report.consistent === null ? "Not reasoned yet."
                                                                   : h("span", { class: "ok" }, "Consistent."));
  }

  let searchTimer = null;
  const input = document.getElementById("search");
  const hits = document.getElementById("hits");
  input.addEventListener("input", () => {
    clearTimeout(searchTimer);
    searchTimer = setTimeout(async () => {
      const q = input.value.trim();
      if (!q) { hits.hidden = true; return; }
      const found = await getJson("/entities?q=" + encodeURIComponent(q));
      hits.replaceChildren(...found.entities.map(e => h("li", {}, h("a", { href: R.entityHref(e.name) },
        h("span", {}, e.name), h("span", { class: "kind" }, e.kind)))));
      if (!found.entities.length) hits.replaceChildren(h("li", { class: "empty" }, "  no entity matches"));
      hits.hidden = false;
    }, 150);
  });
  input.addEventListener("keydown", ev => {
    const first = hits.querySelector("a");
    if (ev.key === "Enter" && first) {
      location.hash = first.getAttribute("href");
      hits.hidden = true;
      input.value = "";
      input.blur();
    }
    if (ev.key === "Escape") hits.hidden = true;
  });
  hits.addEventListener("click", () => { hits.hidden = true; input.value = ""; });
  document.addEventListener("click", ev => { if (!ev.target.closest(".search")) hits.hidden = true; });

  // ------------------------------------------------------------------ consistency
  async function showConsistency() {
    try {
      const report = await getJson("/consistency");
      showStatus(report.consistent);
      const parts = [h("h1", {}, "Consistency"), ...R.warnings(report.warnings)];
      if (report.consistent !== false) parts.push(consistencySummary(report));
      else parts.push(h("p", { class: "hint" }, "Each violation names the axiom it breaks and the individuals " +
        "involved. While the reference is inconsistent, queries and entity pages show the asserted facts only; " +
        "remove or replace one of the facts involved and the next REASON clears the report."));
      report.violations.forEach(v => parts.push(h("div", { class: "card violation" },
        h("div", { class: "message" }, v.message),
        h("div", {}, "Axiom: ", h("span", { class: "mono" }, R.linked(v.axiom, report.links)),
          h("span", { class: "rule" }, "  (rule " + v.rule + ")")),
        h("div", {}, "Individuals: ", v.individuals.map((t, i) => [i ? ", " : "", "?" + t.variable + " = ", R.term(t)])),
        v.why ? h("details", { class: "why", open: "open" }, h("summary", {}, "why? the facts that clash"),
                  R.proofList(v.why.premises, report.links)) : "")));
      show("consistency", ...parts);
    } catch (err) { failure("consistency", err); }
  }

  // ------------------------------------------------------------------ history
  const termText = t => t.name !== undefined ? t.name : (t.value !== undefined ? t.value : t.expression);

  function triples(list, sign, cls) {
    return list.map(t => h("div", { class: cls + " fact", "data-text": [t.s, t.p, t.o].map(termText).join(" ") },
                           sign + " ", R.term(t.s), " ", R.term(t.p), " ", R.term(t.o)));
  }

  // "URGENT" shows what became (or stopped being) URGENT when: only the facts whose words contain it
  function filterHistory() {
    const words = (state.historyFilter || "").toLowerCase().split(/\s+/).filter(Boolean);
    document.querySelectorAll("#history .timeline > li").forEach(li => {
      let shown = 0;
      li.querySelectorAll(".fact").forEach(f => {
        const text = f.dataset.text.toLowerCase();
        f.hidden = !words.every(w => text.includes(w));
        if (!f.hidden) shown += 1;
      });
      li.hidden = words.length > 0 && shown === 0;
    });
  }

  async function showHistory() {
    try {
      const hist = await getJson("/history");
      const parts = [h("h1", {}, "History"), h("p", { class: "hint" },
        `Recording since ${R.time(hist.since)} (when this page was first opened for the reference); ` +
        `the last ${hist.kept} REASONs are kept, newest first.` + (hist.dropped ? ` ${hist.dropped} older ones were dropped.` : "") +
        " Recording makes each REASON compare the inferred facts before and after; stop it with " +
        "DELETE " + base + "/history (e.g. curl -X DELETE).")];
      const filter = h("input", { id: "history-filter", type: "search", placeholder: "only facts with… (e.g. URGENT)",
                                  "aria-label": "filter the history" });
      filter.value = state.historyFilter || "";
      filter.addEventListener("input", () => { state.historyFilter = filter.value; filterHistory(); });
      parts.push(filter);
      if (!hist.events.length) parts.push(h("p", { class: "empty" }, "No REASON since then."));
      parts.push(h("ul", { class: "timeline" }, hist.events.map(ev => {
        const cls = ev.consistency_changed ? (ev.consistent ? "became-consistent" : "became-inconsistent") : "";
        const more = (ev.added_count - ev.added.length) + (ev.removed_count - ev.removed.length);
        return h("li", { class: cls },
          h("span", { class: "when" }, R.time(ev.time)),
          h("span", { class: "meta" }, `REASON #${ev.seq} · ${(ev.reason_seconds * 1000).toFixed(1)} ms · ` +
            `+${ev.added_count} −${ev.removed_count}` + (ev.missed ? ` · ${ev.missed} REASON(s) not recorded` : "")),
          ev.consistency_changed ? h("div", { class: ev.consistent ? "ok" : "removed" },
            ev.consistent ? "became consistent" : "became INCONSISTENT") : "",
          triples(ev.added, "+", "added"), triples(ev.removed, "−", "removed"),
          more > 0 ? h("div", { class: "hint" }, `… and ${more} more facts`) : "",
          !ev.added_count && !ev.removed_count && !ev.consistency_changed ? h("div", { class: "hint" }, "nothing changed") : "");
      })));
      show("history", ...parts);
      filterHistory();
    } catch (err) { failure("history", err); }
  }

  // ------------------------------------------------------------------ the SPARQL console
  // Class and property names are completed from this reference (the search route), not from LOV.
  function entityCompletions(kinds) {
    return async (yasqe, token) => {
      const typed = (token && token.autocompletionString) || "";
      const needle = typed.split(/[#/:]/).pop();
      if (!needle) return [];
      const found = await getJson("/entities?limit=100&q=" + encodeURIComponent(needle));
      return found.entities.filter(e => kinds.includes(e.kind) && e.iri.startsWith(typed)).map(e => e.iri);
    };
  }

  function localCompleters() {
    const Yasqe = Yasgui.Yasqe;
    if (!Yasqe.Autocompleters["topostore-class"]) {
      Yasqe.forkAutocompleter("class", { name: "topostore-class", get: entityCompletions(["class"]) }, false);
      Yasqe.forkAutocompleter("property", { name: "topostore-property", get: entityCompletions(
        ["object property", "data property", "annotation property"]) }, false);
    }
    return ["variables", "topostore-class", "topostore-property"];
  }

  function consoleReady() {
    if (state.yasgui) return state.yasgui;
    // nothing may be fetched from outside the service: no prefix.cc / LOV autocompletion, no share-link parsing
    const completers = localCompleters();
    Yasgui.Yasqe.defaults.autocompleters = completers.slice();
    const endpoint = location.origin + base + "/sparql";
    state.yasgui = new Yasgui(document.getElementById("yasgui"), {
      requestConfig: { endpoint, method: "GET" },
      copyEndpointOnNewTab: true,
      endpointCatalogueOptions: { getData: () => [{ endpoint }] },
      persistenceId: null,
      populateFromUrl: false,
      yasqe: { autocompleters: completers.slice(), consumeShareLink: null, createShareableLink: null },
      yasr: { prefixes: {} },
    });
    // an IRI in the result table opens its entity page here, not the IRI's own (often unreachable) site
    document.getElementById("yasgui").addEventListener("click", ev => {
      const a = ev.target.closest("a.iri");
      if (!a) return;
      ev.preventDefault();
      ev.stopPropagation();
      location.hash = "#entity/" + encodeURIComponent(a.getAttribute("href"));
    }, true);
    return state.yasgui;
  }

  async function showConsole() {
    show("sparql");
    const yasgui = consoleReady();
    if (state.queries) return;
    try {
      state.queries = (await getJson("/queries")).queries;
      document.getElementById("queries").replaceChildren(...state.queries.map(q => h("li", {},
        h("button", { type: "button", "data-query": q.name }, h("b", {}, q.name), h("span", { class: "desc" }, q.description)))));
      document.querySelectorAll("#queries button").forEach(b => b.addEventListener("click", () => {
        const q = state.queries.find(x => x.name === b.dataset.query);
        const tab = yasgui.getTab();
        tab.setQuery(q.text);
        tab.query();
      }));
    } catch (err) { document.getElementById("queries").replaceChildren(h("li", { class: "warning" }, String(err.message))); }
  }

  // ------------------------------------------------------------------ routing and live updates
  function route() {
    const hash = decodeURIComponent(location.hash.replace(/^#/, ""));
    if (hash.startsWith("entity/")) return showEntity(hash.slice(7));
    if (hash === "sparql") return showConsole();
    if (hash === "history") return showHistory();
    if (hash === "consistency") return showConsistency();
    return showOverview();
  }

  // one redraw at a time: REASONs that arrive meanwhile are covered by one more redraw after it
  async function refresh(initial) {
    if (state.busy) { state.again = true; return; }
    state.busy = true;
    try {
      do {
        state.again = false;
        try { showStatus((await getJson("/consistency?brief=true")).consistent); } catch (err) { /* dropped: the view says */ }
        if (initial === true || !location.hash.startsWith("#sparql")) await route();
      } while (state.again);
    } finally { state.busy = false; }
    document.body.dataset.events = String(state.events);
  }

  window.addEventListener("hashchange", route);
  const source = new EventSource(base + "/events");
  source.addEventListener("reason", () => { state.events += 1; refresh(); });
  refresh(true);
  window.topostoreInspector = { refresh, state, entityCompletions };
})();
