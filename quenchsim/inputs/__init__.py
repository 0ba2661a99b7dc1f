"""Every file a user or a study brings, declared once and read one way.

:mod:`quenchsim.inputs.reader` parses TOML (the only module that does) and names the file in an error;
:mod:`quenchsim.inputs.declare` declares a file's tables as frozen dataclasses whose fields carry unit, default,
limits and meaning, and converts a table to one and back. The kinds of file are declared in the modules beside them.
"""

from quenchsim.inputs.declare import REQUIRED, Table, from_table, key_rows, quantity, to_table
from quenchsim.inputs.reader import parse_toml, parse_value, read_toml, reading

__all__ = ["REQUIRED", "Table", "from_table", "key_rows", "quantity", "to_table", "parse_toml", "parse_value",
           "read_toml", "reading"]
