"""Magnitudes the hostile corpus found unbounded in this round's sections (and a [[material]]'s numbers): each
refused in one line naming its field (design.hb_ratio of a book rim gave a zero mass and exit 1; a huge member centre or mechanism
speed ratio overflowed with warnings on stderr)."""

from __future__ import annotations

from pathlib import Path

import pytest
import tomllib

from flyopt.errors import SceneError
from flyopt.io.scene import from_dict

TEXTBOOK = Path(__file__).resolve().parents[2] / "problems" / "textbook"


def _with(name: str, table: str, key: str, value: object, index: int | None = None) -> dict:
    data = tomllib.loads((TEXTBOOK / name).read_text(encoding="utf-8"))
    target = data[table][index] if index is not None else data[table]
    target[key] = value
    return data


@pytest.mark.parametrize(
    ("data", "field", "words"),
    [
        (_with("khurmi-16-14-book-rim.toml", "design", "hb_ratio", 1e-300), "design.hb_ratio", "out of range"),
        (_with("khurmi-16-14-book-rim.toml", "design", "hb_ratio", [0.2, 1e300]), "design.hb_ratio", "out of range"),
        (
            _with("khurmi-16-14-book-rim.toml", "material", "allowable_stress", 1e300, index=0),
            "material[0].allowable_stress",
            "out of range",
        ),
        (
            _with("khurmi-16-14-book-rim.toml", "material", "density", 1e-300, index=0),
            "material[0].density",
            "out of range",
        ),
        (
            _with("khurmi-16-14-book-rim.toml", "material", "max_rim_speed", "1e9 m/s", index=0),
            "material[0].max_rim_speed",
            "out of range",
        ),
        (
            _with("khurmi-16-14-book-rim.toml", "material", "density", "1 kg/m^3", index=0),  # with 7 MPa: 2.6 km/s, ok
            None,
            None,
        ),
        (
            {
                **_with("khurmi-16-14-book-rim.toml", "material", "density", "1 kg/m^3", index=0),
                "material": [{"name": "foam", "density": "1 kg/m^3", "allowable_stress": "100 GPa"}],
                "design": {"geometry": "thin_rim", "materials": ["foam"]},
            },
            "material[0]",
            "beyond any rotor's",
        ),
        (
            _with("seed000-calc7-gear-sine-mechanism-position.toml", "mechanism", "speed_ratio", -1e300),
            "mechanism.speed_ratio",
            "out of range",
        ),
        (
            _with("seed000-calc6-guide-bar-position.toml", "member", "centre", -1e300, index=2),
            "member[2].centre",
            "out of range",
        ),
    ],
)
def test_a_magnitude_beyond_any_wheel_is_refused_in_one_line(data, field, words):
    if field is None:  # within the bounds: read as given
        from_dict(data)
        return
    with pytest.raises(SceneError) as err:
        from_dict(data)
    assert err.value.field == field and words in str(err.value)


@pytest.mark.parametrize(
    ("data", "field", "words"),
    [
        (_with("khurmi-16-14-book-rim.toml", "design", "rim_share", 1e-300), "design.rim_share", "[0.01, 1]"),
        (
            {
                "machine": {"speed": "120 rpm", "delta": 0.05},
                "torque": {
                    "net": {
                        "areas": [1.0, -1.0],
                        "area_unit": "1 m^2",
                        "torque_scale": "1e12 N*m/m",
                        "angle_scale": "1e6 rad/m",
                    }
                },
            },
            "torque.net.areas[0]",
            "beyond any machine's cycle",
        ),
        (  # each scale beyond its dimension's magnitudes is refused at itself (flyopt.units.MAGNITUDES)
            {
                "machine": {"speed": "120 rpm", "delta": 0.05},
                "torque": {
                    "net": {
                        "areas": [1.0, -1.0],
                        "area_unit": "1e300 mm^2",
                        "torque_scale": "1 N*m/mm",
                        "angle_scale": "1 deg/mm",
                    }
                },
            },
            "torque.net.area_unit",
            "is out of range (allowed: a size of 1e-12 to 1e+06 m^2",
        ),
        (
            {"machine": {"speed": "120 rpm", "delta": 0.05}, "torque": {"net": {"areas": ["1e300 J", "-1e300 J"]}}},
            "torque.net.areas[0]",
            "beyond any machine's cycle",
        ),
        (  # the corpus's khurmi-16-5 with area_unit 1e-300: J_F and the rim's mass underflowed to 0 (exit 1)
            {
                "machine": {"speed": "600 rpm", "delta": 0.03},
                "torque": {
                    "net": {
                        "areas": [52, -124, 92, -140, 85, -72, 107],
                        "area_unit": 1e-300,
                        "torque_scale": "600 N*m/mm",
                        "angle_scale": "3 deg/mm",
                    }
                },
            },
            "torque.net.area_unit",
            "1e-300 is out of range (allowed: a size of 1e-12 to 1e+06 m^2",
        ),
        (  # each scale within its magnitudes, their product below a nanojoule an area
            {
                "machine": {"speed": "600 rpm", "delta": 0.03},
                "torque": {
                    "net": {
                        "areas": [52, -124, 92, -140, 85, -72, 107],
                        "area_unit": "1e-12 m^2",
                        "torque_scale": "1e-9 N*m/m",
                        "angle_scale": "1e-9 rad/m",
                    }
                },
            },
            "torque.net.areas[0]",
            "below which no machine's cycle lies",
        ),
        (
            {"machine": {"speed": "120 rpm", "delta": 0.05}, "torque": {"net": {"areas": ["1e-300 J", "-1e-300 J"]}}},
            "torque.net.areas[0]",
            "at least 1e-09 J",
        ),
    ],
)
def test_found_by_the_gallerys_hostile_run(data, field, words):
    """A rim giving 1e-300 of J_F designed a massless rim (exit 1); areas to a huge scale overflowed the sums."""
    with pytest.raises(SceneError) as err:
        from_dict(data)
    assert err.value.field == field and words in str(err.value)
