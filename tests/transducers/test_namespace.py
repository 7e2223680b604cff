"""The public namespace of taxel.transducers and the common interface."""

import dataclasses

import numpy as np
import pytest

import taxel.transducers as tr

TRANSDUCERS = [
    tr.ResistiveTransducer,
    tr.CapacitiveTransducer,
    tr.PiezoelectricTransducer,
    tr.ReflectiveOpticalTransducer,
    tr.FtirTransducer,
    tr.MicrobendTransducer,
    tr.PhotoelasticTransducer,
]


def test_all_is_complete_and_catalogued():
    assert len(tr.__all__) == len(set(tr.__all__))
    assert {name for name in dir(tr) if not name.startswith("_")} == set(tr.__all__)
    for name in tr.__all__:
        assert name in tr.__doc__, f"{name} missing from the catalogue"
        assert getattr(tr, name).__doc__, f"{name} has no docstring"


@pytest.mark.parametrize("cls", TRANSDUCERS, ids=lambda c: c.__name__)
def test_every_transducer_follows_the_protocol(cls):
    default = cls()
    assert isinstance(default, tr.Transducer)
    assert default.quantity in {
        "pressure",
        "strain",
        "stress",
        "displacement",
        "stress_difference",
    }
    assert default.quantity_unit in {"Pa", "-", "m"}
    assert default.quantity in tr.__doc__ and cls.__name__ in tr.__doc__
    first = dataclasses.fields(default)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(default, first, 1.0)


STATIC = {
    tr.ResistiveTransducer: np.linspace(0, 2e5, 11),
    tr.CapacitiveTransducer: np.linspace(-0.4, 0.0, 11),
    tr.ReflectiveOpticalTransducer: np.linspace(0, 0.8e-3, 11),
    tr.PhotoelasticTransducer: np.linspace(0, 3e6, 200),
}


@pytest.mark.parametrize("cls", list(STATIC), ids=lambda c: c.__name__)
def test_default_round_trip_within_two_percent_of_full_scale(cls):
    values = STATIC[cls]
    transducer = cls()
    error = np.abs(transducer.invert(transducer.respond(values)) - values)
    assert np.max(error) < 0.02 * np.max(np.abs(values))
