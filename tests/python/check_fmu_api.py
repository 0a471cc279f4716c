"""Drives a unimo FMU (FMI 2.0 Co-Simulation of the bouncing ball) and its FMI 3.0
Model Exchange twin through FMPy's low-level API: calls in the wrong order and bad
arguments must return fmi2Error/fmi3Error with a coded message through the logger
(never crash), and two instances of one FMU must run side by side, interleaved,
exactly as each runs alone.

Usage: check_fmu_api.py FMI2_CS.fmu FMI3_ME.fmu. Exit code 77 when FMPy is missing.
"""

import ctypes
import sys

try:
    import fmpy
    from fmpy.fmi1 import FMICallException
    from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
    from fmpy.fmi2 import fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE
    from fmpy.fmi3 import FMU3Model
except ImportError as e:
    print(f"skip: {e}")
    sys.exit(77)

MESSAGES = []


def raw(fmu, name, *args):
    """Calls an FMI function of the library directly (those FMPy's class lacks)."""
    function = getattr(fmu.dll, name)
    function.restype = ctypes.c_int
    component = fmu.component if isinstance(fmu.component, ctypes.c_void_p) else ctypes.c_void_p(fmu.component)
    status = function(component, *args)
    if status > 1:
        raise FMICallException(function=name, status=status)


def log2(env, name, status, category, message):
    MESSAGES.append((status, message.decode()))


def log3(env, status, category, message):
    MESSAGES.append((status, message.decode()))


LOGGER2 = fmi2CallbackLoggerTYPE(log2)
CALLBACKS = fmi2CallbackFunctions()
CALLBACKS.logger = LOGGER2
CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(0)
CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(0)


def expect_error(what, call, code):
    """`call` must fail with status 3 and log a message with `code`."""
    del MESSAGES[:]
    try:
        call()
    except FMICallException as e:
        if e.status != 3:
            raise AssertionError(f"{what}: status {e.status}, expected 3")
    else:
        raise AssertionError(f"{what}: no error")
    if not any(status == 3 and code in m for status, m in MESSAGES):
        raise AssertionError(f"{what}: no {code} message in {MESSAGES}")
    print(f"ok: {what}: {MESSAGES[-1][1]}")


def slave(unzipped, md, name):
    fmu = FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName=name,
    )
    fmu.instantiate(callbacks=CALLBACKS)
    return fmu


def start(fmu, vrs, e):
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.setReal([vrs["e"]], [e])
    fmu.exitInitializationMode()


def run_alone(unzipped, md, vrs, e, steps, h):
    fmu = slave(unzipped, md, f"alone{e}")
    start(fmu, vrs, e)
    out = []
    for k in range(steps):
        fmu.doStep(k * h, h)
        out.append(fmu.getReal([vrs["h"], vrs["v"]]))
    fmu.terminate()
    fmu.freeInstance()
    return out


def check_fmi2(path):
    unzipped = fmpy.extract(path)
    md = fmpy.read_model_description(unzipped)
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    fmu = slave(unzipped, md, "order")
    expect_error("fmi2DoStep before initialization", lambda: fmu.doStep(0.0, 0.1), "E4704")
    expect_error("fmi2GetReal of an unknown value reference", lambda: fmu.getReal([10**6]), "E4705")
    expect_error("fmi2GetInteger of a Real", lambda: fmu.getInteger([vrs["h"]]), "E4705")
    fmu.setupExperiment(startTime=0.0)
    expect_error("fmi2ExitInitializationMode before entering it", fmu.exitInitializationMode, "E4704")
    fmu.enterInitializationMode()
    # h's start is the parameter h0 (set h0 instead); v's is a literal with fixed = true.
    expect_error("fmi2SetReal of a state whose start is computed", lambda: fmu.setReal([vrs["h"]], [1.0]), "E4705")
    fmu.exitInitializationMode()
    expect_error("fmi2SetReal of a state's start after initialization", lambda: fmu.setReal([vrs["v"]], [1.0]), "E4705")
    expect_error("fmi2SetReal of a parameter after initialization", lambda: fmu.setReal([vrs["e"]], [0.1]), "E4705")
    expect_error("fmi2DoStep from the wrong time", lambda: fmu.doStep(5.0, 0.1), "E4705")
    buffer = (ctypes.c_double * 2)()
    expect_error("fmi2GetDerivatives in Co-Simulation", lambda: raw(fmu, "fmi2GetDerivatives", buffer, ctypes.c_size_t(2)), "E4704")
    expect_error("fmi2GetReal with a null array", lambda: raw(fmu, "fmi2GetReal", None, ctypes.c_size_t(2), buffer), "E4705")
    fmu.terminate()
    fmu.freeInstance()
    # A wrong GUID: no instance, and the reason logged.
    del MESSAGES[:]
    bad = FMU2Slave(guid="{0}", unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bad")
    try:
        bad.instantiate(callbacks=CALLBACKS)
        raise AssertionError("instantiated with a wrong GUID")
    except Exception as e:
        assert any("E4703" in m for _, m in MESSAGES), MESSAGES
        print(f"ok: wrong GUID refused: {MESSAGES[-1][1]}")
    # Two instances side by side, interleaved, with different restitutions.
    steps, h = 40, 0.1
    alone = {e: run_alone(unzipped, md, vrs, e, steps, h) for e in (0.8, 0.5)}
    a, b = slave(unzipped, md, "a"), slave(unzipped, md, "b")
    start(a, vrs, 0.8)
    start(b, vrs, 0.5)
    for k in range(steps):
        a.doStep(k * h, h)
        b.doStep(k * h, h)
        ya, yb = a.getReal([vrs["h"], vrs["v"]]), b.getReal([vrs["h"], vrs["v"]])
        assert ya == alone[0.8][k], (k, ya, alone[0.8][k])
        assert yb == alone[0.5][k], (k, yb, alone[0.5][k])
    differ = max(abs(x[0] - y[0]) for x, y in zip(alone[0.8], alone[0.5]))
    assert differ > 0.1, differ
    print(f"ok: two instances interleaved over {steps} steps equal their runs alone (they differ by up to {differ:.3f} m)")
    a.terminate()
    b.terminate()
    a.freeInstance()
    b.freeInstance()


def check_fmi3(path):
    unzipped = fmpy.extract(path)
    md = fmpy.read_model_description(unzipped)
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU3Model(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.modelExchange.modelIdentifier,
        instanceName="me3",
    )
    fmu.instantiate(logMessage=fmpy.fmi3.fmi3LogMessageCallback(log3))
    expect_error("fmi3UpdateDiscreteStates before initialization", fmu.updateDiscreteStates, "E4704")
    expect_error("fmi3GetFloat64 of an unknown value reference", lambda: fmu.getFloat64([10**6]), "E4705")
    # A state's start value (initial = "exact") set before the end of initialization.
    [v] = [x for x in md.modelVariables if x.name == "v"]
    assert v.initial == "exact" and float(v.start) == 0.0, (v.initial, v.start)
    fmu.enterInitializationMode(startTime=0.0)
    fmu.setFloat64([vrs["v"]], [5.0])
    assert fmu.getFloat64([vrs["v"]]) == [5.0]
    fmu.exitInitializationMode()
    fmu.updateDiscreteStates()
    fmu.enterContinuousTimeMode()
    states = (ctypes.c_double * 5)()
    expect_error("fmi3GetContinuousStates with a wrong size", lambda: fmu.getContinuousStates(states, 5), "E4705")
    fmu.getContinuousStates(states, 2)
    assert list(states[:2]) == [10.0, 5.0], list(states)
    print("ok: a state's start value set in initialization mode is its initial value")
    expect_error("fmi3GetClock (not provided)", lambda: raw(fmu, "fmi3GetClock", None, ctypes.c_size_t(0), None), "E4702")
    fmu.terminate()
    fmu.freeInstance()


def main():
    check_fmi2(sys.argv[1])
    check_fmi3(sys.argv[2])
    print("all FMI API checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
