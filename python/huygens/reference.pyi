# Type stubs of huygens.reference (the submodule of the extension module).
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

def cauchy_poisson_eta(
    r_m: Union[float, npt.ArrayLike],
    t_s: float,
    *,
    sigma_m: float = 0.1,
    amplitude_m: float = 0.01,
    gravity_mps2: float = 9.81,
    surface_tension_npm: float = 0.072,
    density_kgpm3: float = 1000.0,
    depth_m: Optional[float] = None,
) -> npt.NDArray[np.float64]:
    """The exact linear ring wave of a Gaussian hump released from rest (m)."""

def kelvin_cusp_angle_deg(
    speed_mps: float,
    *,
    gravity_mps2: float = 9.81,
    surface_tension_npm: float = 0.072,
    density_kgpm3: float = 1000.0,
    depth_m: Optional[float] = None,
) -> float:
    """A Kelvin wake's cusp half-angle (deg): 19.47 in deep gravity water."""

def kelvin_transverse_wavelength_m(
    speed_mps: float,
    *,
    gravity_mps2: float = 9.81,
    surface_tension_npm: float = 0.072,
    density_kgpm3: float = 1000.0,
    depth_m: Optional[float] = None,
) -> float:
    """A Kelvin wake's transverse wavelength (m)."""

def measure_kelvin_wake(
    eta: npt.ArrayLike,
    dx_m: float,
    x0_m: float,
    y0_m: float,
    ship: dict[str, float],
    *,
    s_min_m: float = -1.0,
    s_max_m: float = -1.0,
    gravity_mps2: float = 9.81,
) -> dict[str, Any]:
    """The wake's envelope and max-amplitude half-angles and transverse wavelength."""

def martin_moyce_1952() -> list[dict[str, Any]]:
    """Martin & Moyce (1952) surge fronts: series, T, Z."""
