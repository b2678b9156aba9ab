"""Reasoning-latency benchmarks: ``python -m benchmarks [--quick] [--sizes ...] [--steps N] [--out DIR]``.

For generated topological maps (:mod:`topostore.mapgen`) of growing size, each
size in a fresh subprocess so that peak memory belongs to that size alone:

* load time (TBox file + map file into the store) and full materialisation time;
* peak resident memory (``getrusage`` maxrss: Oxigraph's memory is Rust's, which
  ``tracemalloc`` does not see);
* latency of one robot step — REPLACE isIn, now and visitedAt, REASON, query
  canReach and URGENT — with incremental maintenance and with full
  rematerialisation, as median and 95th percentile;
* peers on the same data, each in a subprocess with a time limit: owlrl on
  rdflib (OWL 2 RL closure only — owlrl does not run SWRL rules) and, when
  ``java`` and Owlready2 are installed, Owlready2 + Pellet.

Results go to ``--out`` (default ``out/bench/``) as a printed table, a CSV,
JSON and a PNG plot.
"""
