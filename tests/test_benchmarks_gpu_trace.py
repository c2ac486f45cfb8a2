"""benchmarks/gpu_trace.py's summary of a profiler trace: busy, idle, copies, kernels."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from gpu_trace import summarise  # noqa: E402


def test_summary_of_device_events():
    meta = [
        {"ph": "M", "name": "process_name", "pid": 1, "args": {"name": "/device:GPU:0"}},
        {"ph": "M", "name": "process_name", "pid": 2, "args": {"name": "/host:CPU"}},
    ]
    device = [("fft", 0, 10), ("fusion", 10, 5), ("MemcpyD2H", 20, 1), ("fft", 30, 10),
              ("MemcpyD2H", 45, 1)]  # fmt: skip
    events = meta + [{"ph": "X", "pid": 1, "tid": 1, "name": k, "ts": t, "dur": d}
                     for k, t, d in device]  # fmt: skip
    events.append({"ph": "X", "pid": 2, "tid": 1, "name": "host work", "ts": 0, "dur": 99})
    out = summarise({"traceEvents": events}, iterations=2)
    assert out["device_events"] == 5
    assert out["span_ms"] == pytest.approx(0.046)
    assert out["busy_ms"] == pytest.approx(0.027)
    assert out["idle_ms"] == pytest.approx(0.019)  # 15-20, 21-30, 40-45
    assert out["d2h_per_iteration"] == pytest.approx(1.0)
    assert out["kernels"][0] == {"name": "fft", "calls": 2, "ms": pytest.approx(0.02)}


def test_a_trace_without_device_events():
    assert summarise({"traceEvents": []}, iterations=3) == {"device_events": 0}
