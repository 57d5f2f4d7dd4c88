"""Outputs: the fields of every result with their SI units, the schema version, and the files.

A ring beside the input (io/): the studies write their chunks through it as
they run, and the report and the command line read its units. JSON, Parquet
and CSV, with nulls for missing values (:mod:`~flyopt.outputs.results`).
"""
