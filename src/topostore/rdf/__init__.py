"""RDF before any store: every IRI (``vocab``), terms and literals, syntaxes, the one SPARQL lexer,
safe file I/O and blank nodes as skolem IRIs.  The bottom of the data path: it imports nothing of
topostore but :mod:`topostore.errors`.
"""
