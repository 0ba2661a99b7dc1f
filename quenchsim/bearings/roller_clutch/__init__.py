"""Two-way roller clutch (Okada et al., "Electronically controlled two-way roller clutch for 4WD transfer
cases", NTN Technical Review 69 (2001) 39): roller load from the transmitted torque through the cam
wedge with contact and ring compliance (:mod:`.wedge`), Hertz line contacts and max-shear depths
(:mod:`quenchsim.bearings.hertz`), the outer ring by Lame, by the exact discrete-load series (:mod:`.ring`)
and by plane-stress FE (:mod:`.fe`); :func:`analyse` puts them together."""

from quenchsim.bearings.roller_clutch.analysis import ClutchState, FECheck, analyse, fe_check
from quenchsim.bearings.roller_clutch.ring import DiscreteLoadRing, LameRing, lame_ring, ring_response
from quenchsim.bearings.roller_clutch.wedge import (ClutchGeometry, Engagement, WedgeHold, engage,
                                                    free_wedge_angle_for, palmgren_approach_m, roller_contacts,
                                                    roller_from_line_contact, torque_Nm, wedge_angle_rad, wedge_hold)

__all__ = ["ClutchGeometry", "ClutchState", "DiscreteLoadRing", "Engagement", "FECheck", "LameRing", "analyse",
           "engage", "fe_check", "free_wedge_angle_for", "lame_ring", "palmgren_approach_m", "ring_response",
           "roller_contacts", "roller_from_line_contact", "torque_Nm", "WedgeHold", "wedge_angle_rad", "wedge_hold"]
