"""Batched open-loop rollouts on a thread pool, in the spirit of mujoco.rollout.

        state, sensordata = simlab.rollout.rollout(model, data, initial_state, control)

initial_state is (nbatch or 1) x nstate with nstate = mj_stateSize(model,
mjSTATE_FULLPHYSICS) (get it with mj_getState); control is (nbatch or 1) x (nstep or 1) x
ncontrol, ncontrol = mj_stateSize(model, control_spec). Singleton dimensions are tiled.
The results are nbatch x nstep x nstate states and nbatch x nstep x nsensordata sensor
values after each step. Rollouts run on nthread threads (default: one per MjData given,
the calling thread for a single MjData), one MjData each, with the GIL released; a
rollout's result does not depend on the thread count.
"""
import atexit

import numpy as np

from simlab import _simlab

__all__ = ["Rollout", "rollout", "shutdown_persistent_pool"]


class Rollout:
    """A pool of nthread threads for rollouts (0: run on the calling thread)."""

    def __init__(self, *, nthread=None):
        self.nthread = 0 if nthread is None else int(nthread)
        if self.nthread < 0:
            raise ValueError("nthread must be >= 0")
        self._pool = _simlab._Rollout(nthread=self.nthread)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Stops the threads (they finish the work they have)."""
        self._pool = None

    def rollout(self, model, data, initial_state, control=None, *,
                control_spec=_simlab.mjtState.mjSTATE_CTRL, skip_checks=False, nstep=None,
                initial_warmstart=None, state=None, sensordata=None, chunk_size=None):
        """Rolls out len(initial_state) trajectories; returns (state, sensordata).

        skip_checks: the arrays are already C-ordered float64 of the full sizes (nbatch
        rollouts, nstep given); no shapes are inferred, tiled or allocated (the engine
        still checks every size).
        """
        if self._pool is None:
            raise RuntimeError("rollout requested after the thread pool was closed")
        models = [model] if isinstance(model, _simlab.MjModel) else list(model)
        datas = _datas_for(models[0], data, max(self.nthread, 1))
        control_spec = int(control_spec)
        if skip_checks:
            # nbatch from the initial states; one model for all, or the first nbatch.
            nstate = _simlab.mj_stateSize(models[0], int(_simlab.mjtState.mjSTATE_FULLPHYSICS))
            nbatch = np.asarray(initial_state).size // max(nstate, 1)
            models = models * nbatch if len(models) == 1 else models[:nbatch]
            self._pool.rollout(models, datas, int(nstep), control_spec, initial_state,
                               initial_warmstart, control, state, sensordata,
                               int(chunk_size or 0))
            return state, sensordata
        if control_spec & ~int(_simlab.mjtState.mjSTATE_USER):
            raise ValueError("control_spec can only contain bits in mjSTATE_USER")

        # Arrays as float64, C order, with their leading dimensions.
        initial_state = _as_array(initial_state, 2, "initial_state")
        initial_warmstart = _as_array(initial_warmstart, 2, "initial_warmstart")
        control = _as_array(control, 3, "control")
        state = _output(state, "state")
        sensordata = _output(sensordata, "sensordata")

        # nbatch and nstep from whichever arrays give them.
        nbatch = _infer(0, 1, initial_state=initial_state, initial_warmstart=initial_warmstart,
                        control=control, state=state, sensordata=sensordata)
        if len(models) > 1:
            if nbatch not in (1, len(models)):
                raise ValueError(f"nbatch inferred as {nbatch} but model is length {len(models)}")
            nbatch = len(models)
        nstep = _infer(1, nstep or 1, control=control, state=state, sensordata=sensordata)

        # Sizes must agree across models and with the arrays.
        nstate = _simlab.mj_stateSize(models[0], int(_simlab.mjtState.mjSTATE_FULLPHYSICS))
        ncontrol = _simlab.mj_stateSize(models[0], control_spec)
        for m in models[1:]:
            if (_simlab.mj_stateSize(m, int(_simlab.mjtState.mjSTATE_FULLPHYSICS)) != nstate or
                    _simlab.mj_stateSize(m, control_spec) != ncontrol or m.nv != models[0].nv or
                    m.nsensordata != models[0].nsensordata):
                raise ValueError("models are not compatible")
        _check_last(nstate, initial_state=initial_state, state=state)
        _check_last(ncontrol, control=control)
        _check_last(models[0].nv, initial_warmstart=initial_warmstart)
        _check_last(models[0].nsensordata, sensordata=sensordata)
        if initial_state is None:
            raise ValueError("initial_state is required")

        # Tile singleton dimensions; allocate the outputs.
        models = models * nbatch if len(models) == 1 else models
        initial_state = _tile(initial_state, nbatch)
        initial_warmstart = _tile(initial_warmstart, nbatch)
        control = _tile(control, nbatch, nstep)
        if state is None:
            state = np.empty((nbatch, nstep, nstate))
        if sensordata is None:
            sensordata = np.empty((nbatch, nstep, models[0].nsensordata))
        _check_shape(state, (nbatch, nstep, nstate), "state")
        _check_shape(sensordata, (nbatch, nstep, models[0].nsensordata), "sensordata")

        self._pool.rollout(models, datas, nstep, control_spec, initial_state, initial_warmstart,
                           control, state, sensordata, int(chunk_size or 0))
        return state, sensordata


_persistent = None  # the pool persistent_pool=True reuses


def rollout(model, data, initial_state, control=None, *, nthread=None,
            control_spec=_simlab.mjtState.mjSTATE_CTRL, skip_checks=False, nstep=None,
            initial_warmstart=None, state=None, sensordata=None, chunk_size=None,
            persistent_pool=False):
    """Rolls out trajectories (see the module's documentation); returns (state, sensordata).

    nthread defaults to len(data) when data is a list of several MjData, else 0 (the calling
    thread). With more threads than MjData, the missing ones are made from the model.
    persistent_pool keeps the threads for the next call with the same thread count
    (shutdown_persistent_pool() ends them).
    """
    global _persistent
    if nthread is None:
        nthread = len(data) if isinstance(data, (list, tuple)) and len(data) > 1 else 0
    if persistent_pool:
        if _persistent is None or _persistent.nthread != nthread:
            shutdown_persistent_pool()
            _persistent = Rollout(nthread=nthread)
        pool = _persistent
    else:
        pool = Rollout(nthread=nthread)
    try:
        return pool.rollout(model, data, initial_state, control, control_spec=control_spec,
                            skip_checks=skip_checks, nstep=nstep,
                            initial_warmstart=initial_warmstart, state=state,
                            sensordata=sensordata, chunk_size=chunk_size)
    finally:
        if not persistent_pool:
            pool.close()


def shutdown_persistent_pool():
    """Ends the threads of the pool persistent_pool=True keeps (also at exit)."""
    global _persistent
    if _persistent is not None:
        _persistent.close()
    _persistent = None


atexit.register(shutdown_persistent_pool)


def _datas_for(model, data, count):
    """count MjData: those given, then fresh ones for the model."""
    datas = [data] if isinstance(data, _simlab.MjData) else list(data)
    if not datas:
        raise ValueError("data must be an MjData or a non-empty list of them")
    while len(datas) < count:
        datas.append(_simlab.MjData(model))
    return datas


def _as_array(value, ndim, name):
    """None, or value as a C-ordered float64 array padded to ndim dimensions in front."""
    if value is None:
        return None
    array = np.ascontiguousarray(value, dtype=np.float64)
    if array.ndim > ndim:
        raise ValueError(f"{name} can have at most {ndim} dimensions")
    while array.ndim < ndim:
        array = array[np.newaxis]
    return np.ascontiguousarray(array)


def _output(value, name):
    """An output array given by the caller: written in place, so it must be exact."""
    if value is None:
        return None
    if (not isinstance(value, np.ndarray) or value.dtype != np.float64 or
            not value.flags.c_contiguous or not value.flags.writeable):
        raise ValueError(f"{name} must be a writable C-contiguous float64 numpy array")
    if value.ndim != 3:
        raise ValueError(f"{name} must have 3 dimensions")
    return value


def _infer(axis, default, **arrays):
    """The size of `axis` the arrays agree on (1 is a wildcard)."""
    size = None
    for name, array in arrays.items():
        if array is None or array.shape[axis] == 1:
            continue
        if size is not None and array.shape[axis] != size:
            raise ValueError(f"dimension {axis} of {name} is {array.shape[axis]}, expected {size}")
        size = array.shape[axis]
    return size if size is not None else default


def _check_last(size, **arrays):
    for name, array in arrays.items():
        if array is not None and array.shape[-1] != size:
            raise ValueError(f"trailing dimension of {name} is {array.shape[-1]}, expected {size}")


def _check_shape(array, shape, name):
    if array.shape != shape:
        raise ValueError(f"{name} has shape {array.shape}, expected {shape}")


def _tile(array, nbatch, nstep=None):
    """Repeats singleton batch (and step) dimensions."""
    if array is None:
        return None
    if array.shape[0] == 1 and nbatch > 1:
        array = np.repeat(array, nbatch, axis=0)
    if nstep is not None and array.shape[1] == 1 and nstep > 1:
        array = np.repeat(array, nstep, axis=1)
    return np.ascontiguousarray(array)
