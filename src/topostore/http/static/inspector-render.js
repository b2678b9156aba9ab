// The inspector's building blocks: DOM elements, entity links, facts marked asserted or inferred,
// proof trees. Text is always set as text (never as HTML), so names from the ontology cannot inject markup.
"use strict";
window.InspectorRender = (function () {
  function h(tag, attrs, ...children) {
    const el = document.createElement(tag);
    Object.entries(attrs || {}).forEach(([k, v]) => {
      if (v === undefined || v === null || v === false) return;
      if (k === "class") el.className = v; else if (k === "text") el.textContent = v; else el.setAttribute(k, v);
    });
    children.flat(Infinity).forEach(c => el.append(c instanceof Node ? c : document.createTextNode(String(c))));
    return el;
  }

  function entityHref(name) { return "#entity/" + encodeURIComponent(name); }

  function entityLink(name) { return h("a", { href: entityHref(name), class: "entity" }, name); }

  // A term of the JSON: {name, iri} (an entity: a link), {value, datatype} (a literal), {expression}.
  // the standard vocabularies (rdf:type, owl:Thing) are words, not entities of the reference: no link
  const STANDARD = /^(rdf|rdfs|owl|xsd):/;

  function term(t) {
    if (t.name !== undefined && STANDARD.test(t.name)) return h("span", { class: "vocab", title: t.iri }, t.name);
    if (t.name !== undefined) return h("a", { href: entityHref(t.name), title: t.iri, class: "entity" }, t.name);
    if (t.value !== undefined) {
      return h("span", { class: "literal" }, t.value,
               h("span", { class: "datatype" }, t.language ? "@" + t.language : t.datatype));
    }
    return h("code", {}, t.expression);
  }

  // Text of a proof node or axiom with the words that are entities of the reference as links.
  function linked(text, links) {
    const out = h("span", {});
    String(text).split(/([\s(),{}]+)/).forEach(part => {
      out.append(links && Object.prototype.hasOwnProperty.call(links, part) ? entityLink(part)
                                                                              : document.createTextNode(part));
    });
    return out;
  }

  function chip(inferred) {
    return h("span", { class: "chip " + (inferred ? "inferred" : "asserted") }, inferred ? "inferred" : "asserted");
  }

  function statusChip(status) {
    return h("span", { class: "chip " + status.replace(" ", "") }, status);
  }

  // One derivation tree (topostore.explain's JSON): the fact, the rule and its origin, the premises below.
  function proofNode(node, links) {
    const li = h("li", {}, linked(node.triple, links), " ");
    if (node.status === "inferred") {
      li.append(h("span", { class: "rule" }, "← " + (node.rule || "") + (node.origin ? ": " : ""),
                  linked(node.origin || "", links)));
      if (node.conditions) {
        const values = Object.entries(node.bindings || {}).map(([k, v]) => k + " = " + v).join(", ");
        li.append(h("div", { class: "bindings" }, "where " + node.conditions + (values ? " with " + values : "")));
      }
      if ((node.premises || []).length) li.append(proofList(node.premises, links));
    } else {
      li.append(statusChip(node.status));
    }
    return li;
  }

  function proofList(nodes, links) { return h("ul", { class: "proof" }, nodes.map(n => proofNode(n, links))); }

  function why(fact, links) {
    if (!fact.inferred || !fact.why) return "";
    const details = h("details", { class: "why" }, h("summary", {}, "why?"));
    details.append(proofList([fact.why], links));
    return details;
  }

  // A table of facts: one row per fact, its cells from `columns`, the asserted/inferred chip and the proof.
  function factTable(facts, columns, links) {
    if (!facts || !facts.length) return h("p", { class: "empty" }, "none");
    const head = h("tr", {}, columns.map(c => h("th", {}, c.title)), h("th", {}, ""), h("th", {}, ""));
    const rows = facts.map(f => h("tr", { class: f.inferred ? "inferred" : "asserted" },
                                  columns.map(c => h("td", {}, c.cell(f))),
                                  h("td", { class: "status" }, chip(f.inferred)), h("td", {}, why(f, links))));
    return h("table", { class: "facts" }, h("thead", {}, head), h("tbody", {}, rows));
  }

  function legend() {
    return h("div", { class: "legend" }, chip(false), " stated in the ontology or by a command   ", chip(true),
             " derived by the reasoner (yellow, as in Protégé): open “why?” for the proof, down to asserted facts");
  }

  function warnings(list) { return (list || []).map(w => h("div", { class: "warning" }, w)); }

  function time(seconds) { return new Date(seconds * 1000).toLocaleTimeString(); }

  return { h, legend, term, linked, chip, statusChip, proofList, factTable, warnings, entityLink, entityHref, time };
})();
