"""One 2-process Dask cluster shared by a module's study tests (the tiny study is in
tests/conftest.py)."""

import pytest


@pytest.fixture(scope="module")
def cluster_address():
    """A LocalCluster with 2 worker processes (1 thread each), shared by a module's tests."""
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        yield cluster.scheduler_address
