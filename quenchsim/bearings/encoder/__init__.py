"""Magnetic encoder of a rotation-sensor bearing (H. Ito & T. Koike, NTN Technical Review 69 (2001) 108; T. Koike &
Y. Nagano, ibid. 112): the field of a multipole magnetised layer against air gap and pole pitch (closed form,
:mod:`.field`; 2-D magnetostatic FE check, :mod:`.fe`), Hall-sensor switching over a revolution and the paper's
pulse-accuracy measures (:mod:`.pulses`)."""

from quenchsim.bearings.encoder.field import (Encoder, field_T, layer_factor, magnet_data, pole_centre_field_T,
                                              remanence_at_temperature_T, remanence_for_field_T, working_gap_m)
from quenchsim.bearings.encoder.stray import stray_field_margin_T
from quenchsim.bearings.encoder.pulses import PulseMetrics, RingEncoder, pulse_metrics, sensor_field_T

__all__ = ["Encoder", "PulseMetrics", "RingEncoder", "field_T", "layer_factor", "magnet_data", "pole_centre_field_T",
           "pulse_metrics", "remanence_at_temperature_T", "remanence_for_field_T", "sensor_field_T",
           "stray_field_margin_T", "working_gap_m"]
