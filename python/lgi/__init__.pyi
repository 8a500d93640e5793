# Type stub of the package lgi (python/README.md). Arrays are NumPy float64
# (step: int64); shapes in the comments, n = number of samples.
from os import PathLike
from typing import Any, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
SceneLike = Union["Scene", str, PathLike[str]]

class Scene:
    """A scene: the body, its torques, the initial state and the [run] defaults.

    Scene(**keys) takes the keys of a scene file (tables as dicts, arrays of
    tables as lists of dicts); bad input raises ValueError naming the key as
    lgi does ('Scene(**kwargs): [body] inertia: ...').
    """
    def __init__(self, **keys: Any) -> None: ...
    @staticmethod
    def from_file(path: str) -> Scene:
        """Reads a scene file; ValueError with lgi's message ('<file>:<line>: [table] key: ...')."""
    @staticmethod
    def from_toml(text: str, name: str = "<string>") -> Scene:
        """Parses scene TOML text; `name` stands for the file in messages."""
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def file(self) -> str: ...
    @property
    def toml(self) -> str: ...
    @property
    def inertia(self) -> FloatArray:
        """J about the reference point, kg m^2, (3, 3)."""
    @property
    def mass(self) -> Optional[float]: ...
    @property
    def center_of_mass(self) -> Optional[FloatArray]: ...
    @property
    def R0(self) -> FloatArray:
        """Initial attitude, body -> space, (3, 3)."""
    @property
    def Pi0(self) -> FloatArray:
        """Initial body angular momentum, kg m^2/s, (3,)."""
    @property
    def t_end(self) -> Optional[float]: ...
    @property
    def dt(self) -> Optional[float]: ...
    @property
    def tol(self) -> Optional[float]: ...
    @property
    def free_body(self) -> bool: ...
    @property
    def invariants(self) -> list[str]: ...

class SimulationResult:
    """The trajectory of one simulate() run (see help(lgi.SimulationResult))."""
    t: FloatArray                      # (n,) s
    step: npt.NDArray[np.int64]        # (n,)
    R: FloatArray                      # (n, 3, 3) body -> space
    q: FloatArray                      # (n, 4) (w, x, y, z)
    Pi: FloatArray                     # (n, 3) kg m^2/s
    omega: FloatArray                  # (n, 3) 1/s
    energy: FloatArray                 # (n,) kg m^2/s^2
    orthogonality_error: FloatArray    # (n,)
    angular_momentum_space: Optional[FloatArray]  # (n, 3), free bodies
    euler_zxz: Optional[FloatArray]    # (n, 3), Euler-angle baselines
    invariants: dict[str, FloatArray]  # name -> (n,)
    errors: dict[str, FloatArray]      # name -> (n,), against the first sample
    diagnostics: dict[str, Any]        # steps, rhs_evaluations, ..., cpu_seconds, status, ok
    scheme: str
    scene: str
    out: Optional[str]
    def __len__(self) -> int: ...

class Stepper:
    """A fixed-step scheme advanced by your own loop; n calls of step() equal one
    simulate() of n steps for schemes without per-run constants."""
    def __init__(self, scene: SceneLike, scheme: str, dt: float, t0: float = 0.0) -> None: ...
    def step(self, n: int = 1) -> None:
        """Takes n steps (GIL released); RuntimeError with the run's message if one fails."""
    @property
    def state(self) -> dict[str, FloatArray]:
        """{'R': (3, 3), 'Pi': (3,)}"""
    @state.setter
    def state(self, value: dict[str, Any]) -> None:
        """{'Pi': (3,), 'R': (3, 3)} or {'Pi': (3,), 'gamma': (3,)}; ValueError if R is not a
        rotation to 1e-12 or gamma is zero. t and the step count are kept."""
    @property
    def t(self) -> float: ...
    @property
    def dt(self) -> float: ...
    @property
    def scheme(self) -> str: ...
    @property
    def stats(self) -> dict[str, Any]:
        """steps, rhs_evaluations, rejected_steps, newton_iterations_max, newton_failures, cpu_seconds."""

def schemes() -> list[dict[str, Any]]:
    """Every registered scheme: name, order, order_with_torque, family, kind, base,
    properties (dict of bools), support, reference, notes (`lgi schemes --json`)."""

def scenes_dir(directory: Optional[str] = None) -> str:
    """The shipped scenes' folder ($LGI_SCENES_DIR, else beside the package)."""

def scenes(directory: Optional[str] = None) -> list[dict[str, Any]]:
    """The scene files of a folder: file, path, name, description, invariants, free_body,
    t_end, dt, tol (`lgi scenes`)."""

def simulate(
    scene: SceneLike,
    scheme: str,
    t_end: Optional[float] = None,
    dt: Optional[float] = None,
    tol: Optional[float] = None,
    save_every: int = 1,
    out: Optional[Union[str, PathLike[str]]] = None,
    force: bool = False,
    retry_halving: int = 0,
) -> SimulationResult:
    """Integrate a scene with a scheme (lgi simulate); with out= also write its H5MD file.

    Defaults from the scene's [run]; ValueError for bad settings, an unknown scheme or a
    scheme that does not apply (lgi's messages); RuntimeError for a failed run. GIL released.
    """

def exact_free_flow(scene: SceneLike, times: Union[float, Sequence[float], FloatArray]) -> tuple[FloatArray, FloatArray]:
    """(R (n, 3, 3), Pi (n, 3)) of the exact free-body flow at `times`; ValueError for a scene with torques."""

def sweep(
    spec: Union[str, PathLike[str], dict[str, Any]],
    threads: int = 1,
    out: Optional[str] = None,
    force: bool = False,
) -> np.ndarray:
    """lgi sweep in-process: the /sweep table as a structured array (one row per trajectory)."""

# The atlas of heavy tops (docs/atlas.md): the tables of lgi equilibria,
# lgi bifurcation, lgi region and lgi poincare as dicts of NumPy arrays under
# the column names of the commands' HDF5 files (experiments/EQUILIBRIA.md,
# REGION.md, POINCARE.md); integer columns are int64.
Table = dict[str, Any]

def equilibria(scene: SceneLike, l: float) -> Table:
    """Every relative equilibrium at l (lgi equilibria --l), sorted by h: omega, gamma (n, 3),
    angular_momentum (n, 3), l, h, branch, g1, g2, stability, nonlinearly_stable, fold, residual,
    and branches {id: kind}."""

def bifurcation(
    scene: SceneLike,
    samples: int = 400,
    appelrot: Optional[Sequence[float]] = None,
    appelrot_h: Optional[str] = None,
) -> Table:
    """Every branch sampled, with its folds (lgi bifurcation): the columns of equilibria() and
    branches; with appelrot= (a Kovalevskaya top) also the dicts appelrot, appelrot_equilibria,
    appelrot_range."""

def region(scene: SceneLike, l: float, h: float, grid: int = 120) -> Table:
    """lgi region --l --h: the dicts potential, critical_points, components (with topology: a name
    per component), and topology (str), resolved (bool), u_constant (bool), l, h, grid."""

def region_cells(
    scene: SceneLike,
    l_range: Union[str, tuple[float, float, int]],
    h_range: Union[str, tuple[float, float, int]],
    grid: int = 120,
    samples: int = 400,
) -> Table:
    """lgi region --cells: the dicts cells (l, h, h_min, topology (n_l, n_h), components, euler,
    euler_morse, resolved, topology_names) and equilibria (l, h, omega, branch, stability, fold),
    and unresolved (int)."""

def poincare(
    scene: SceneLike,
    l: float,
    h: float,
    ics: int,
    t_end: float,
    dt: Optional[float] = None,
    megno: bool = False,
    lyapunov: bool = False,
    seed: int = 0,
    axis: Optional[str] = None,
    section: Optional[str] = None,
    scheme: Optional[str] = None,
    max_events: int = 100000,
    threads: int = 1,
    out: Optional[str] = None,
    force: bool = False,
) -> Table:
    """lgi poincare in-process: the dicts events (one row per crossing: index, direction, t, gamma,
    phi, theta, sheet, ...) and sweep (one row per orbit; lyapunov, megno when asked), parameters
    (the file's /parameters attributes) and out."""
def indicators(
    scene: SceneLike,
    t_end: Optional[float] = None,
    dt: Optional[float] = None,
    states: Optional[Union[str, PathLike[str], dict[str, Any]]] = None,
    spectrum: bool = False,
    seed: int = 0,
    rtol: float = 0.05,
    gali: bool = False,
    gali_samples: int = 100,
    gali_spacing: Literal["log", "linear"] = "log",
) -> dict[str, Any]:
    """The records of `lgi indicators` (experiments/INDICATORS.md), one row per state: index,
    lyapunov, lyapunov_last_half, megno, t_end, converged (int64 0/1), angular_momentum (n, 3),
    gamma (n, 3), and spectrum (n, 6) with spectrum=True. With gali=True: log10_gali_2 ..
    log10_gali_6 (n,) at T and "gali", a dict of the file's /gali group: index, t (rows,) and
    log10_gali (rows, 5), one row per (state, sample time). states: None (the scene's initial
    state), a state file (HDF5/CSV with angular_momentum and gamma) or a dict of (n, 3) arrays;
    a Cardan scene takes None and adds cardan_angles and cardan_momenta (1, 3)."""

def frequencies(
    scene: SceneLike,
    t_end: float,
    observables: Optional[Sequence[str]] = None,
    terms: int = 5,
    window_order: int = 1,
    scheme: str = "split-symmetric@kahan-li8",
    dt: Optional[float] = None,
    output_dt: Optional[float] = None,
    tol: Optional[float] = None,
) -> dict[str, Any]:
    """The tables of `lgi frequencies` (experiments/FREQUENCIES.md, docs/frequency_analysis.md):
    'frequencies' (observable (list of str), term, frequency, amplitude, phase, period: one row per
    observable and term, terms by decreasing amplitude) and 'diffusion' (observable, frequency,
    frequency_first_half, frequency_second_half, relative_change, log10_relative_change, mean: one
    row per observable); 'samples' and 'output_dt'. observables: names as in the trajectory file
    (angular_momentum_1..3, gamma_1..3, angular_velocity_1..3; default all nine), or complex pairs
    'A+iB' (signed frequencies). ValueError on bad
    arguments, RuntimeError if the run fails."""

def quantum_spectrum(
    scene: SceneLike,
    hbar: float,
    m: int = 0,
    jmax: int = 40,
    levels: int = 20,
    jmax_step: int = 4,
    tol: float = 1e-8,
) -> dict[str, Any]:
    """The levels of `lgi quantum` (experiments/QUANTUM.md): the /spectrum columns index, energy, j,
    m, k, parity, converged (int64 0/1), change_with_jmax, k_conserved as arrays, and symmetry,
    parity_classes, moments, weight (J and c in the frame used), dimension, method."""

def periodic_orbit(
    scene: SceneLike,
    angular_momentum: FloatArray,
    gamma: FloatArray,
    period: float,
    h: Optional[float] = None,
    l: Optional[float] = None,
    dt: float = 2e-3,
    shooting_points: int = 1,
) -> dict[str, Any]:
    """One periodic orbit by Newton's method (single shooting, or multiple shooting on shooting_points
    segments) from a point and a period guess (experiments/PERIODIC.md): the /periodic columns for one
    row, plus converged, iterations and the (6, 6) monodromy."""

def continue_family(
    scene: SceneLike,
    l: Optional[float] = None,
    seed: Optional[tuple[FloatArray, FloatArray, float]] = None,
    steps: int = 10,
    h_step: float = 0.01,
    dt: float = 2e-3,
    amplitude: float = 1e-4,
    h_range: Optional[tuple[float, float]] = None,
    events: bool = True,
    branch_switching: bool = True,
    continue_in: str = "h",
    l_step: float = 0.01,
    l_range: Optional[tuple[float, float]] = None,
    shooting_points: int = 1,
    seeds_from_poincare: Optional[str] = None,
    poincare_rows: Optional[Sequence[int]] = None,
    poincare_points: Optional[Sequence[tuple[float, float, int]]] = None,
    returns: int = 1,
    manifolds: int = 0,
    manifold_periods: float = 4.0,
    manifold_epsilon: float = 1e-5,
    direction: float = 1.0,
) -> dict[str, Any]:
    """Families of periodic orbits with their events and doubled families, continued in h at fixed l or
    in l at fixed h (continue_in): the Lyapunov families of the stable relative equilibria (no seed), one
    family from a seed, or one per seed of a `lgi poincare` file (seeds_from_poincare, poincare_rows,
    poincare_points), with the manifolds of its hyperbolic orbits (manifolds=N: d["manifolds"]); the
    /periodic columns of `lgi periodic`, failures and l_file (experiments/PERIODIC.md)."""

def tangent_flow(
    scene: SceneLike,
    state: dict[str, Any],
    v: FloatArray,
    dt: float,
    steps: int = 1,
    t0: float = 0.0,
) -> dict[str, Any]:
    """`steps` RKMK4 steps of the state with tangent vector(s) v ((6,) or (6, k), k <= 6; not
    renormalised): {'R', 'Pi', 'v', 't'}. state as Stepper.state (Pi with R or gamma)."""

def spectral_statistics(
    levels: FloatArray,
    classes: Optional[Sequence[int]] = None,
    unfolded: bool = False,
    lengths: Optional[Sequence[float]] = None,
    bin_width: float = 0.1,
    s_max: float = 4.0,
    degree: int = 5,
) -> dict[Any, Any]:
    """Spectral statistics of levels (docs/spectral_statistics.md): spacings (mean 1), histogram,
    brody {beta, standard_error, log_likelihood, bound}, lengths, number_variance(_error),
    rigidity(_error) (Dyson-Mehta Delta3) and the poisson and goe references; with classes, a dict
    {label: that dict} (too_few=True and only levels for a class too small). unfolded=True: the
    levels are already unfolded (Weyl's law, preferred); else a polynomial staircase fit of degree."""
