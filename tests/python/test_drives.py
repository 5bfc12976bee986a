

def test_current_rates_stop_at_a_failed_row():
    """A row that does not solve splits the trajectory: the rates of each run of solved rows are
    its own differences (one-sided beside the gap), the failed row keeps its zeros."""
    t, q, qd, qdd = manoeuvre(n=60)
    q[25, 2] = 50.0  # unreachable
    platform = driven(rotor_inertia=1e-4, winding_inductance=2e-3)
    sol = platform.inverse(q, qd, qdd, "massless", t=t)
    assert list(np.flatnonzero(sol.status)) == [25]
    for run in (slice(0, 25), slice(26, 60)):
        close(sol.current_rate[run], np.gradient(sol.current[run], t[run], axis=0), rel=1e-10)
    assert not np.any(sol.current_rate[25]) and not np.any(sol.voltage[25])
