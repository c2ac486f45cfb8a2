"""``study run --device cuda``: one local worker per visible GPU, each pinned to its own
through ``CUDA_VISIBLE_DEVICES`` (checked on the CPU: the workers' environments)."""

import os
import stat

import pytest

from roughcontact import ParameterError
from roughcontact.studies import _gpus, cluster, runner


@pytest.mark.parametrize(
    ("value", "gpus"),
    [("0,2", ("0", "2")), (" 1 , GPU-ab12 ", ("1", "GPU-ab12")), ("", ()), ("-1", ()),
     ("NoDevFiles", ())],
)  # fmt: skip
def test_visible_gpus_from_cuda_visible_devices(value, gpus):
    assert _gpus.visible_gpus({"CUDA_VISIBLE_DEVICES": value}) == gpus


def test_visible_gpus_from_nvidia_smi(tmp_path, monkeypatch):
    smi = tmp_path / "nvidia-smi"
    smi.write_text("#!/bin/sh\necho 'GPU 0: NVIDIA H100 (UUID: GPU-1)'\n"
                   "echo 'GPU 1: NVIDIA H100 (UUID: GPU-2)'\necho '  MIG 1g.10gb'\n")  # fmt: skip
    smi.chmod(smi.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("PATH", f"{tmp_path}{os.pathsep}{os.environ['PATH']}")
    assert _gpus.visible_gpus({}) == ("0", "1")
    monkeypatch.setenv("PATH", str(tmp_path / "nowhere"))
    assert _gpus.visible_gpus({}) == ()  # no driver: no GPU


def test_each_local_worker_sees_only_its_gpu():
    client, local = cluster.connect(None, None, gpus=("3", "5"))
    try:
        seen = client.run(lambda: os.environ.get("CUDA_VISIBLE_DEVICES"))
    finally:
        cluster.close(client, local)
    assert sorted(seen.values()) == ["3", "5"]  # one worker per GPU, by default


def test_more_workers_than_gpus_share_them_in_turn():
    spec = {"cls": object, "options": {"nthreads": 1}}
    pinned = [_gpus.pinned_worker(spec, ("0", "1"), i)["options"]["env"] for i in range(3)]
    assert [e["CUDA_VISIBLE_DEVICES"] for e in pinned] == ["0", "1", "0"]
    assert _gpus.pinned_worker(spec, (), 0) is spec and "env" not in spec["options"]


def test_run_study_pins_the_local_cluster_for_cuda_only(make_study, tmp_path, monkeypatch):
    asked = []

    def connect(scheduler, workers, security, dashboard, gpus):
        asked.append(gpus)
        raise ParameterError("stop here")

    monkeypatch.setattr(runner, "check_device", lambda device: device)  # no GPU here
    monkeypatch.setattr(runner, "visible_gpus", lambda: ("7", "8"))
    monkeypatch.setattr(cluster, "connect", connect)
    for device, out in (("cuda", "a"), ("cuda:1", "b"), (None, "c")):
        with pytest.raises(ParameterError, match="stop here"):
            runner.run_study(make_study(), tmp_path / out, device=device, progress=False)
    assert asked == [("7", "8"), (), ()]
