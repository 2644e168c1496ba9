#!/usr/bin/env python3
"""The manifests `nut city` writes, in both layouts, validate against the JSON Schema of
docs/CITY.md (read from the document itself, so the two cannot drift), and the schema refuses a
manifest with one field broken (so the check can fail).

    city_schema_test.py NUT CITY.md OUTPUT_DIR
"""
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

from jsonschema import Draft202012Validator


def schema_of(doc: Path) -> dict:
    text = doc.read_text()
    section = text[text.index("## JSON Schema"):]
    block = re.search(r"```json\n(.*?)```", section, re.S)
    return json.loads(block.group(1))


def main() -> int:
    nut, doc, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    validator = Draft202012Validator(schema_of(doc))
    failures = 0
    for layout in ("streets", "grid"):
        folder = out / f"schema-{layout}"
        shutil.rmtree(folder, ignore_errors=True)
        subprocess.run([nut, "city", "--count", "12", "--out", str(folder), "--layout", layout, "--quiet"],
                       check=True)
        manifest = json.loads((folder / "city.json").read_text())
        errors = [e.message for e in validator.iter_errors(manifest)]
        if errors:
            print(f"{layout}: city.json breaks the schema: {errors[0]}")
            failures += 1
        broken = dict(manifest, buildings=[dict(manifest["buildings"][0], hni="../outside.png")])
        if validator.is_valid(broken):
            print(f"{layout}: the schema accepts a building outside its folder")
            failures += 1
    print("city_schema_test:", "FAILED" if failures else "manifests of both layouts validate")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
