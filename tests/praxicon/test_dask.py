"""The build on a Dask cluster (a LocalCluster of 2 worker processes) equals the serial one."""

from __future__ import annotations

from praxicon import build, read_dataset


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def test_dask_local_cluster_gives_the_serial_praxicon(manifest, tmp_path):
    import dask
    from dask.distributed import Client, LocalCluster

    actions = read_dataset(manifest)
    build(actions, tmp_path / "serial", progress=False, log=lambda s: None)
    # the cluster's scratch space in the test's folder, not dask's default in /tmp, kept
    with dask.config.set({"temporary-directory": str(tmp_path / "dask-scratch")}), \
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                         dashboard_address=None) as cluster, Client(cluster) as client:
        result = build(actions, tmp_path / "dask", executor=client, progress=False,
                       log=lambda s: None)
        assert len(client.scheduler_info()["workers"]) == 2
    assert result.learnt == ("moves.step", "moves.wave")
    assert _files(tmp_path / "serial") == _files(tmp_path / "dask")
