"""Arm configuration: files load, bad values are rejected naming the field and the fix."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from verigraph.arm import ArmConfig, ArmConfigError, driver_from_executor, load_arm_config
from verigraph.arm.config import parse_arm_config

YAML = """\
driver: xarm
mode: real
host: 192.168.1.185
audit_log: {audit}
workspace: {{min: [0.15, -0.4, 0.02], max: [0.6, 0.4, 0.5]}}
keep_out:
  - {{name: camera_post, min: [0.5, 0.3, 0.0], max: [0.6, 0.4, 0.5]}}
speed_m_s: 0.1
max_speed_m_s: 0.15
grip_force_n: 10
max_force_n: 20
motion_timeout_s: 12
home: {{x: 0.3, y: 0.0, z: 0.3}}
xarm: {{gripper: lite6}}
"""


def test_yaml_config_loads_every_field(tmp_path: Path) -> None:
    path = tmp_path / "arm.yaml"
    path.write_text(YAML.format(audit=tmp_path / "audit.jsonl"))
    config = load_arm_config(path)
    assert config.driver == "xarm" and config.mode == "real"
    assert config.workspace.max == (0.6, 0.4, 0.5)
    assert config.keep_out[0].name == "camera_post"
    assert config.xarm.gripper == "lite6"
    assert config.motion_timeout_s == 12


def test_json_config_loads_and_defaults_to_dry_run(tmp_path: Path) -> None:
    path = tmp_path / "arm.json"
    path.write_text(json.dumps({"driver": "pybullet"}))
    config = load_arm_config(path)
    assert config.mode == "dry-run"
    assert config.workspace.contains(config.home.point())


@pytest.mark.parametrize(("data", "field", "fix_mentions"), [
    ({"driver": "ur5"}, "driver", "pybullet, rosbridge, xarm"),
    ({"driver": "pybullet", "mode": "fast"}, "mode", "dry-run"),
    ({"driver": "pybullet", "speed_m_s": 0.5}, "config", "README"),
    ({"driver": "pybullet", "workspace": {"min": [0.5, 0, 0], "max": [0.4, 1, 1]}},
     "workspace", "min < max"),
])
def test_bad_values_name_the_field_and_fix(data: dict[str, object], field: str,
                                           fix_mentions: str) -> None:
    with pytest.raises(ArmConfigError) as err:
        parse_arm_config(data)
    assert err.value.field is not None and err.value.field.startswith(field)
    assert err.value.fix is not None and fix_mentions in err.value.fix


@pytest.mark.parametrize(("data", "message"), [
    ({"driver": "pybullet", "speed_m_s": 0.3, "max_speed_m_s": 0.25}, "exceeds max_speed_m_s"),
    ({"driver": "pybullet", "grip_force_n": 50}, "exceeds max_force_n"),
    ({"driver": "pybullet", "home": {"x": 2.0, "y": 0, "z": 0.3}}, "outside the workspace"),
    ({"driver": "pybullet", "keep_out": [{"name": "post", "min": [0.3, -0.1, 0.4],
                                          "max": [0.4, 0.1, 0.5]}]}, "inside keep-out zone"),
    ({"driver": "xarm", "mode": "real", "host": "10.0.0.2"}, "needs an audit_log"),
    ({"driver": "pybullet", "mode": "real", "audit_log": "a.jsonl"}, "it is a simulator"),
    ({"driver": "xarm", "mode": "sim", "host": "10.0.0.2"}, "it drives hardware"),
    ({"driver": "rosbridge", "mode": "sim", "host": "h"}, "simulated_backend"),
    ({"driver": "rosbridge", "mode": "sim", "rosbridge": {"simulated_backend": True}},
     "needs a host"),
])
def test_inconsistent_configs_are_rejected(data: dict[str, object], message: str) -> None:
    with pytest.raises(ArmConfigError, match=message):
        parse_arm_config(data)


def test_unreadable_and_malformed_files_are_clear_errors(tmp_path: Path) -> None:
    with pytest.raises(ArmConfigError, match="cannot read") as err:
        load_arm_config(tmp_path / "missing.yaml")
    assert err.value.field == "arm config"
    bad = tmp_path / "bad.yaml"
    bad.write_text("driver: [pybullet\n")
    with pytest.raises(ArmConfigError, match="not valid"):
        load_arm_config(bad)


def test_executor_names() -> None:
    assert driver_from_executor("arm:pybullet") == "pybullet"
    assert driver_from_executor("arm:xarm") == "xarm"
    for bad in ("arm:ur5", "arm", "sim2d:pybullet", "arm:"):
        with pytest.raises(ArmConfigError) as err:
            driver_from_executor(bad)
        assert err.value.field == "executor"
        assert err.value.fix == "use arm:pybullet, arm:rosbridge, arm:xarm"


def test_overrides_are_validated_too() -> None:
    config = ArmConfig(driver="pybullet")
    assert config.with_overrides(mode="sim").mode == "sim"
    with pytest.raises(ArmConfigError):
        config.with_overrides(speed_m_s=1.0)
