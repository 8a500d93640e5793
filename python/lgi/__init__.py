"""lgi: Lie-group integrators for rigid-body dynamics on SO(3) x R^3, from Python.

The rigid body with a fixed point (free body, heavy tops, gyroscope, springs,
drives), integrated on its natural state space: the attitude R (body -> space)
and the body angular momentum Pi. The same schemes, scenes and output as the
command line `lgi` (python/README.md):

    import lgi
    book = lgi.Scene.from_file("experiments/scenes/dzhanibekov_book_axis2.toml")
    run = lgi.simulate(book, "rkmk4", t_end=14.0, dt=1e-3)
    run.t, run.R, run.q, run.Pi, run.errors["energy"], run.diagnostics["cpu_seconds"]

Functions: schemes(), scenes(), scenes_dir(), simulate(), exact_free_flow(),
sweep(), indicators(), tangent_flow(), spectral_statistics() (docs/spectral_statistics.md), quantum_spectrum(),
periodic_orbit(), continue_family() (experiments/PERIODIC.md), frequencies() (NAFF, docs/frequency_analysis.md),
and the atlas of heavy tops (docs/atlas.md): equilibria(),
bifurcation(), region(), region_cells(), poincare(); classes: Scene, Stepper, SimulationResult. Units are SI and the
conventions those of docs/conventions.md: quaternions (w, x, y, z), scalar
first, body -> space; matrices row-major. Long calls release the GIL.
"""

from ._lgi import Scene, Stepper, exact_free_flow, indicators, scenes, scenes_dir, schemes, sweep, tangent_flow
from ._lgi import spectral_statistics
from ._lgi import quantum_spectrum
from ._lgi import continue_family, periodic_orbit
from ._lgi import frequencies
from ._lgi import bifurcation, equilibria, poincare, region, region_cells
from ._lgi import _simulate

__all__ = [
    "Scene",
    "SimulationResult",
    "Stepper",
    "bifurcation",
    "continue_family",
    "equilibria",
    "exact_free_flow",
    "frequencies",
    "indicators",
    "periodic_orbit",
    "poincare",
    "quantum_spectrum",
    "region",
    "region_cells",
    "scenes",
    "scenes_dir",
    "schemes",
    "simulate",
    "spectral_statistics",
    "sweep",
    "tangent_flow",
]


class SimulationResult:
    """The trajectory of one lgi.simulate() run, as NumPy arrays (n samples).

    Attributes, as in the H5MD file `lgi simulate` writes (experiments/OUTPUT.md):
      t (n,)                  time, s
      step (n,)               step number of each sample (int64)
      R (n, 3, 3)             attitude, body -> space (the scheme's own matrix)
      q (n, 4)                unit quaternion (w, x, y, z) of R, as /particles/body/orientation
      Pi (n, 3)               body angular momentum, kg m^2/s
      omega (n, 3)            body angular velocity, 1/s
      energy (n,)             kg m^2/s^2
      orthogonality_error (n,)  |R^T R - I|_F
      angular_momentum_space (n, 3) or None   m = R Pi (free bodies)
      euler_zxz (n, 3) or None                (psi, theta, phi) of the Euler-angle baselines
      invariants              dict name -> (n,): each scalar invariant of the scene (/observables)
      errors                  dict name -> (n,): each invariant's error against the first sample
                              (relative; orthogonality absolute), as `lgi simulate` summarises them
      diagnostics             dict: steps, rhs_evaluations, rejected_steps, newton_iterations_max,
                              newton_failures, cpu_seconds (stepping alone), output_seconds,
                              t_final, status, ok
      scheme, scene           the scheme's and the scene's names
      out                     the file written, or None
    """

    __slots__ = (
        "t", "step", "R", "q", "Pi", "omega", "energy", "orthogonality_error",
        "angular_momentum_space", "euler_zxz", "invariants", "errors", "diagnostics",
        "scheme", "scene", "out",
    )

    def __init__(self, fields):
        for name in self.__slots__:
            setattr(self, name, fields[name])

    def __len__(self):
        return len(self.t)

    def __repr__(self):
        d = self.diagnostics
        return (f"<lgi.SimulationResult {self.scheme} on {self.scene!r}: {len(self.t)} samples, "
                f"t = {self.t[0] if len(self.t) else 0:g} .. {d['t_final']:g}, {d['steps']} steps, "
                f"cpu {d['cpu_seconds']:.3g} s>")


def simulate(scene, scheme, t_end=None, dt=None, tol=None, save_every=1, out=None,
             force=False, retry_halving=0, output_dt=None):
    """Integrate a scene with a scheme: lgi simulate, returning NumPy arrays.

    scene:   an lgi.Scene, or the path of a scene file
    scheme:  a registered name (lgi.schemes(); `lgi schemes`)
    t_end:   final time (s); default: the scene's [run] t_end
    dt:      fixed step (s), or an adaptive scheme's first trial step; default [run] dt
    tol:     an adaptive scheme's tolerance; default [run] tol
    save_every: keep every N-th step (the initial and final states always)
    out:     if given, also write the H5MD trajectory file `lgi simulate --out` writes
             (same layout and values; command_line and utc_start differ)
    force:   replace an existing `out`
    retry_halving: fixed-step schemes: redo a failed implicit step as halves, N deep
    output_dt: keep the states at t0, t0 + output_dt, ... and t_end instead of every
             save_every-th step (lgi simulate --output-dt): interpolated inside the steps
             of a scheme with dense output, landed on by the other adaptive schemes; a
             fixed-step scheme needs a whole multiple of its step

    The run settings resolve as on the command line (flags, then [run], else
    ValueError naming the flag: '--dt: ...'). A bad scheme name or a scheme that
    does not apply to the scene raises ValueError with lgi's message; a run that
    fails (a blow-up, an implicit solve that does not converge) raises
    RuntimeError with the message lgi prints ('<scheme> on <file>: <status>').
    The GIL is released during the run. Returns a SimulationResult.
    """
    if out is not None:
        out = str(out)
    return SimulationResult(_simulate(scene, scheme, t_end, dt, tol, save_every, out, force,
                                      retry_halving, output_dt))
