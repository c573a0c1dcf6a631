"""Fuzz 22a, classes K, N, M, A, H, P, W, T and debatables D7, D8 (issue 35).

Each test is a reproducer of the fuzz report with the refusal or documented result the fix gives.
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
import yaml

from fusion.book import claims as C

ROOT = Path(__file__).resolve().parents[1]


# K: the claim schema stays read-only for callers, and load validates against a plain copy jsonschema can read
def test_k_schema_is_a_json_schema_and_read_only():
    plain = json.loads(json.dumps(C.SCHEMA, default=dict))   # the documented way to a plain schema
    jsonschema.Draft202012Validator.check_schema(plain)
    with pytest.raises(TypeError):
        C.SCHEMA["required"] = []


@pytest.mark.parametrize("entry", [
    {"label": "x", "margin": {"relative": 0.05}, "zzz": 1},   # an extra field
    {"margin": {"relative": 0.05}},                          # no label
    {"label": "x", "margin": {"relative": -1}},              # a negative margin
    3.0,                                                      # not an object
])
def test_k_load_reports_a_quantities_subschema_error(tmp_path, entry):
    doc = yaml.safe_load((ROOT / "book" / "claims" / "lecture003.yaml").read_text(encoding="utf-8"))
    doc["quantities"]["mse"] = entry
    p = tmp_path / "lecture003.yaml"
    p.write_text(yaml.safe_dump(doc, allow_unicode=True), encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match=r"quantities"):
        C.load(p)
    # the schema load runs (not only load's own Python checks) reports it
    assert list(jsonschema.Draft202012Validator(C._PLAIN_SCHEMA).iter_errors(doc))
