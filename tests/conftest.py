import os
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

# Servers started by tests keep their default episode store (SQLite) in a fresh
# directory, never in the user's data directory: one per session for module-wide
# servers, and one per test (below) so that no test sees another's episodes.
SESSION_DATA_HOME = tempfile.mkdtemp(prefix="verigraph-test-data-")
os.environ["XDG_DATA_HOME"] = SESSION_DATA_HOME
# Never let a test reach for a model hub.
os.environ.setdefault("HF_HUB_OFFLINE", "1")
sys.path.insert(0, str(Path(__file__).parent))


def pytest_ignore_collect(collection_path: Path, config: pytest.Config) -> bool | None:
    """`pytest -m fast` (scripts/test.sh --fast) reads only the modules marked fast, so
    the tier runs with the `dev` extra alone: the others may import extras (torch,
    pybullet, gymnasium, unified-planning) at module level."""
    if (config.getoption("markexpr") == "fast" and collection_path.suffix == ".py"
            and collection_path.name.startswith("test_")):
        return "pytest.mark.fast" not in collection_path.read_text(encoding="utf-8")
    return None


def pytest_unconfigure(config: pytest.Config) -> None:
    """The session's data directory goes with the session (servers are stopped by then)."""
    shutil.rmtree(SESSION_DATA_HOME, ignore_errors=True)


@pytest.fixture(scope="session")
def anyio_backend() -> str:
    """Async tests (marked anyio) run on asyncio, the backend the server runs on."""
    return "asyncio"


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    """A local Ray (2 CPUs, no dashboard) for one module's tests, shut down after; a
    module using it skips when the scale extra (ray) is not installed."""
    ray = pytest.importorskip("ray", reason="the scale extra (ray) is not installed")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        yield
    finally:
        ray.shutdown()


@pytest.fixture(autouse=True)
def _private_data_home(tmp_path_factory: pytest.TempPathFactory,
                       monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path_factory.mktemp("data-home")))
    yield


@pytest.fixture(params=["memory", "sqlite", "redis"])
def store_url(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[str]:
    """Each store kind in turn; Redis is emptied first (a module using this imports
    store_helpers.redis_url, which starts it)."""
    if request.param == "memory":
        yield "memory://"
    elif request.param == "sqlite":
        yield f"sqlite:///{tmp_path / 'episodes.db'}"
    else:
        url = request.getfixturevalue("redis_url")
        import redis
        redis.Redis.from_url(url).flushdb()
        yield url
