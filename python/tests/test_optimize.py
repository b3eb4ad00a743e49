"""jellysim.optimize: the CLI's `jellysim optimize`, the plan a dict or a path (docs/control.md)."""
import pytest

import jellysim

PLAN = {
    "cycles": 2,
    "objective": "speed",
    "sense": "maximize",
    "algorithm": "cobyla",
    "evaluations": 3,
    "seed": 1,
    "set": {"tank.cells": [48, 96]},
    "variables": {"jellyfish.frequency": [0.5, 1.2], "jellyfish.contract_fraction": [0.15, 0.6]},
}


def test_a_dict_plan_returns_the_summary(tmp_path):
    summary = jellysim.optimize(PLAN, out=tmp_path)
    assert summary["status"] == "ok" and summary["command"] == "optimize"
    assert summary["evaluations"] == 3
    assert set(summary["best_variables"]) == {"jellyfish.frequency", "jellyfish.contract_fraction"}
    assert summary["best_objective"] >= summary["baseline_objective"]
    for name in ("evaluations.csv", "best.toml", "progress.png", "summary.json"):
        assert (tmp_path / name).is_file()


def test_a_bad_field_raises_input_error_naming_it(tmp_path):
    with pytest.raises(jellysim.InputError) as e:
        jellysim.optimize(dict(PLAN, algorithm="simplex"), out=tmp_path / "bad")
    assert e.value.field == "algorithm"
    assert not (tmp_path / "bad").exists()
