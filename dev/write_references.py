"""Write the key references of docs/reference/ from the declarations in quenchsim/inputs/
(quenchsim.inputs.references): ``python dev/write_references.py`` after a declaration changed."""

from pathlib import Path

from quenchsim.inputs.references import REFERENCES

ROOT = Path(__file__).resolve().parents[1]

if __name__ == "__main__":
    for name, write in REFERENCES.items():
        (ROOT / name).write_text(write())
        print(f"wrote {name}")
