"""Mode II crack toolkit (Fujii, Maeda & Ohtsuka, "New test method for mode II fatigue crack growth in hard
steels", NTN Technical Review 69 (2001) 53): the specimen's K_II and parasitic K_I from the paper's printed fits
with the test-condition checks (:mod:`.sif`), Hertz subsurface stresses of line and elliptical contacts
(:mod:`.subsurface`) and the critical subsurface crack size versus contact pressure (:mod:`.rcf`)."""

from quenchsim.bearings.mode2.rcf import (CriticalCrack, critical_crack, ellipticity_for, inclusion_over_critical,
                                          shear_range_factor)
from quenchsim.bearings.mode2.sif import (F_I, F_II, SpecimenState, crack_data, penny_critical_diameter_m,
                                          penny_K_II_max, penny_K_III_max, specimen_state)
from quenchsim.bearings.mode2.subsurface import (PassStresses, effective_shear_range, elliptical_contact_stresses,
                                                 line_contact_stresses)

__all__ = ["CriticalCrack", "F_I", "F_II", "PassStresses", "SpecimenState", "crack_data", "critical_crack",
           "effective_shear_range", "ellipticity_for", "elliptical_contact_stresses", "inclusion_over_critical", "line_contact_stresses",
           "penny_K_III_max", "penny_K_II_max", "penny_critical_diameter_m", "shear_range_factor", "specimen_state"]
