"""What a seated person feels: the vestibular system as linear filters (docs/perception.md).

The otoliths sense the specific force f (the non-gravitational acceleration, z up: (0, 0, +g)
at rest) and the semicircular canals the angular velocity w, both in the head's frame. Each axis
of each organ is one transfer function

    H(s) = gain * s^m * prod(tau_z s + 1) / prod(tau_p s + 1)

with the published time constants of one model ("telban": Telban & Cardullo 2005, NASA
CR-2005-213747, whose constants docs/perception.md lists with what could be checked):

    canal:    w_hat/w = tau_a tau_L s^2 (tau_N s + 1) / ((tau_a s + 1)(tau_L s + 1)(tau_S s + 1))
              tau_L = 5.73 s (cupula), tau_a = 80 s (adaptation), tau_N = 0.06 s (lead),
              tau_S = 0.005 s
    otolith:  f_hat/f = K (tau_a s + 1) / ((tau_L s + 1)(tau_S s + 1))
              K = 0.4, tau_a = 10 s (lead), tau_L = 5 s, tau_S = 0.016 s

The filters run in their modal (diagonal) state-space form, one state per pole, discretised
exactly for an input held constant over each sample (zero-order hold): for a pole p = -1/tau,
x[k+1] = exp(p dt) x[k] + tau (1 - exp(p dt)) u[k] and y[k] = D u[k] + sum r x[k], with the
residues r and the direct term D of the partial fractions of H. At a step or any other input that
is constant between samples the outputs are the continuous response at the sample times.

>>> import numpy as np, stewart
>>> t = np.arange(0, 10, 0.01)
>>> w = np.zeros((t.size, 3)); w[1:, 2] = 0.5          # a 0.5 rad/s yaw step after the first sample
>>> felt = stewart.perception(t, np.tile([0, 0, 9.81], (t.size, 1)), w)
>>> felt.angular_velocity.shape, round(float(felt.specific_force[-1, 2]), 4)  # at rest: K g
((1000, 3), 3.924)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Tuple, Union

import numpy as np

from .arrays import rows3, times

#: The relative tolerance on the sample spacing: the filters are discretised for one time step.
UNIFORM_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Channel:
    """One transfer function H(s) = gain * s^differentiators * prod(tau s + 1 for tau in leads)
    / prod(tau s + 1 for tau in lags); time constants in seconds. The lags must be distinct and
    positive (one modal state each), H proper (differentiators + len(leads) <= len(lags))."""
    gain: float
    differentiators: int
    leads: Tuple[float, ...]
    lags: Tuple[float, ...]

    def __post_init__(self) -> None:
        lags = tuple(float(x) for x in self.lags)
        if not lags or not all(math.isfinite(x) and x > 0 for x in lags):
            raise ValueError(f"lags = {lags}: at least one, each a positive finite time "
                             "constant [s]")
        if len(set(lags)) != len(lags):
            raise ValueError(f"lags = {lags} repeat a time constant: give distinct ones "
                             "(a repeated pole has no modal form here)")
        if not all(math.isfinite(float(x)) for x in self.leads) or not math.isfinite(self.gain):
            raise ValueError(f"gain = {self.gain}, leads = {self.leads}: finite numbers only")
        if self.differentiators < 0 or self.differentiators + len(self.leads) > len(lags):
            raise ValueError(f"{self.differentiators} differentiators and {len(self.leads)} "
                             f"leads over {len(lags)} lags: the transfer function must be proper")

    def numerator(self, s):
        """The numerator gain * s^m * prod(tau s + 1) at s."""
        value = self.gain * s ** self.differentiators
        for tau in self.leads:
            value = value * (tau * s + 1.0)
        return value

    def modes(self) -> Tuple[float, np.ndarray, np.ndarray]:
        """(D, tau, r): H(s) = D + sum r_i / (s + 1/tau_i), the partial fractions of H."""
        tau = np.array(self.lags, dtype=np.float64)
        proper = self.differentiators + len(self.leads) == len(tau)
        direct = self.gain * float(np.prod(self.leads)) / float(np.prod(tau)) if proper else 0.0
        residues = np.empty_like(tau)
        for i, tau_i in enumerate(tau):
            p = -1.0 / tau_i
            others = np.prod([tau_j * p + 1.0 for j, tau_j in enumerate(tau) if j != i])
            residues[i] = self.numerator(p) / (tau_i * others)
        return direct, tau, residues


@dataclass(frozen=True)
class VestibularModel:
    """A vestibular model: the otolith channel (specific force to perceived specific force, each
    axis) and the canal channel (angular velocity to perceived angular velocity, each axis)."""
    name: str
    otolith: Channel
    canal: Channel
    source: str


TELBAN = VestibularModel(
    name="telban",
    otolith=Channel(gain=0.4, differentiators=0, leads=(10.0,), lags=(5.0, 0.016)),
    canal=Channel(gain=80.0 * 5.73, differentiators=2, leads=(0.06,), lags=(80.0, 5.73, 0.005)),
    source="Telban, R. J. & Cardullo, F. M. (2005), Motion Cueing Algorithm Development: "
           "Human-Centered Linear and Nonlinear Approaches, NASA CR-2005-213747")

#: The models by name (docs/perception.md: the equations, their sources, what could be checked).
MODELS = {"telban": TELBAN}
#: How the filters start: "steady" (the first sample held since forever: a person sitting at
#: rest feels the resting specific force, not a 1 g step at t[0]) or "rest" (zero states).
INITIAL_STATES = ("steady", "rest")


class Perceived(NamedTuple):
    """The perceived specific force [m/s2] (otoliths) and angular velocity [rad/s] (canals), (N, 3)
    each in the head frame of the input."""
    specific_force: np.ndarray
    angular_velocity: np.ndarray


def perception(t, specific_force, angular_velocity, model: Union[str, VestibularModel] = "telban",
               initial: str = "steady") -> Perceived:
    """The specific force and angular velocity a person feels, per axis, from the ones applied to
    the head: t (N,) [s] uniformly spaced, specific_force (N, 3) [m/s2] and angular_velocity (N, 3)
    [rad/s] in the head frame, each held over its sample. model is a name of MODELS or a
    VestibularModel; initial one of INITIAL_STATES. Returns Perceived(specific_force,
    angular_velocity), (N, 3) each. ValueError names a bad argument."""
    t = times("t", t, None)
    if t.shape[0] < 2:
        raise ValueError(f"t has {t.shape[0]} sample(s): give at least 2")
    dt = _time_step(t)
    f = rows3("specific_force", specific_force, t.shape[0])
    w = rows3("angular_velocity", angular_velocity, t.shape[0])
    vestibular = _model(model)
    if initial not in INITIAL_STATES:
        raise ValueError(f"initial = {initial!r}: one of {', '.join(INITIAL_STATES)}")
    return Perceived(filter_channel(vestibular.otolith, dt, f, initial),
                     filter_channel(vestibular.canal, dt, w, initial))


def filter_channel(channel: Channel, dt: float, u: np.ndarray,
                   initial: str = "steady") -> np.ndarray:
    """channel's response to u (N, k) sampled every dt [s], each column held over its sample
    (exact zero-order-hold discretisation of the modal form); initial as in perception."""
    try:
        from scipy.signal import lfilter  # only the filters need scipy (as calibration does)
    except ImportError:
        raise ImportError("stewart.perception needs scipy (its lfilter runs the recursions): "
                          "pip install 'stewart[cueing]' (from a checkout: pip install '.[cueing]')") from None
    direct, tau, residues = channel.modes()
    y = direct * u
    for tau_i, r_i in zip(tau, residues):
        a = math.exp(-dt / tau_i)
        b = -tau_i * math.expm1(-dt / tau_i)  # tau (1 - a), accurate when dt << tau
        x0 = tau_i * u[0] if initial == "steady" else np.zeros(u.shape[1])
        # x[k] with x[0] = x0: lfilter's output y[k] = b u[k-1] + a y[k-1], its state gives x[0].
        x, _ = lfilter([0.0, b], [1.0, -a], u, axis=0, zi=x0.reshape(1, -1))
        y = y + r_i * x
    return y


def _time_step(t: np.ndarray) -> float:
    dt = (t[-1] - t[0]) / (t.shape[0] - 1)
    worst = int(np.argmax(np.abs(np.diff(t) - dt)))
    if abs(t[worst + 1] - t[worst] - dt) > UNIFORM_TOLERANCE * dt:
        raise ValueError(f"t is not uniformly spaced: t[{worst + 1}] - t[{worst}] = "
                         f"{t[worst + 1] - t[worst]!r} s against a mean step of {dt!r} s; "
                         "resample the signals on a uniform grid (numpy.interp)")
    return float(dt)


def _model(model) -> VestibularModel:
    if isinstance(model, VestibularModel):
        return model
    if isinstance(model, str) and model in MODELS:
        return MODELS[model]
    raise ValueError(f"model = {model!r}: one of {', '.join(MODELS)} or a VestibularModel")
