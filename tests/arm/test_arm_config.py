"""Arm configuration: files load, bad values are rejected naming the field and the fix."""

from __future__ import annotations

import json
import math
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
    ({"driver": "pybullet", "speed_m_s": 0.5}, "speed_m_s", "max_speed_m_s (0.25)"),
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


ABSURD = [  # what a careless or hostile operator file might say, and the field named
    ({"workspace": {"min": [0.2, -0.4, 0.0], "max": [math.inf, 0.4, 0.5]}}, "workspace",
     "finite"),
    ({"workspace": {"min": [-200, -200, 0.0], "max": [200, 200, 200]}}, "workspace",
     "|x| and |y| <= 0.855 m"),
    ({"workspace": {"min": [0.2, -0.4, -0.3], "max": [0.6, 0.4, 0.5]}}, "workspace.min",
     "min z >= 0.0 m"),
    ({"workspace": {"min": [0.2, -0.4, 0.0], "max": [0.6, 0.4, 1.5]}}, "workspace.max",
     "max z <= 1.188 m"),
    ({"speed_m_s": 1e6, "max_speed_m_s": math.inf}, "max_speed_m_s", "finite"),
    ({"speed_m_s": 1.0, "max_speed_m_s": 1e6}, "max_speed_m_s", "<= 1.7 m/s"),
    ({"grip_force_n": 1e9, "max_force_n": 1e9}, "max_force_n", "<= 70.0 N"),
    ({"max_location_age_s": 1e9}, "max_location_age_s", "less than or equal to 10"),
    ({"confirm_timeout_s": 1e9}, "confirm_timeout_s", "less than or equal to 600"),
    ({"deadman_s": 0}, "deadman_s", "greater than 0"),
]


@pytest.mark.parametrize(("changes", "field", "allowed"), ABSURD)
def test_absurd_limits_are_rejected_naming_field_and_range(
        changes: dict[str, object], field: str, allowed: str) -> None:
    with pytest.raises(ArmConfigError) as err:
        parse_arm_config({"driver": "pybullet", **changes})
    assert err.value.field is not None and err.value.field.startswith(field)
    assert allowed in str(err.value)


def test_xarm_hard_limits_are_its_own() -> None:
    with pytest.raises(ArmConfigError, match=r"<= 1.0 m/s"):
        parse_arm_config({"driver": "xarm", "max_speed_m_s": 1.5, "speed_m_s": 0.2})


@pytest.mark.parametrize(("changes", "field"), [
    ({"audit_log": "/dev/null"}, "audit_log"),
    ({"audit_log": "/proc/version/audit.jsonl"}, "audit_log"),
    ({"xarm": {"set_reduced_boundary": False}}, "xarm.set_reduced_boundary"),
    ({"agent_may_reset": True}, "agent_may_reset"),
])
def test_real_mode_refuses_a_log_that_keeps_nothing_and_an_open_fence(
        tmp_path: Path, changes: dict[str, object], field: str) -> None:
    data = {"driver": "xarm", "mode": "real", "host": "192.168.1.185",
            "audit_log": str(tmp_path / "audit.jsonl"), **changes}
    with pytest.raises(ArmConfigError) as err:
        parse_arm_config(data)
    assert err.value.field == field and err.value.fix


def test_the_fence_can_be_turned_off_only_by_the_loud_flag(tmp_path: Path) -> None:
    config = parse_arm_config({"driver": "xarm", "mode": "real", "host": "192.168.1.185",
                               "audit_log": str(tmp_path / "audit.jsonl"),
                               "xarm": {"set_reduced_boundary": False},
                               "unsafe_disable_controller_fence": True})
    assert not config.xarm.set_reduced_boundary
