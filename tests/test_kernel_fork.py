"""tools/kernel_fork.py: notebook kernels forked from a server with the imports done are new processes that run a
notebook as a kernel started from nothing does, and any other environment gets a kernel started from nothing."""

import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
kernel_fork = pytest.importorskip("kernel_fork")  # tools/kernel_fork.py (needs nbclient)
nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="fork and Unix sockets: the runner's Linux path")

CELL = "import os, sys\nprint(os.getpid(), os.getppid(), os.getcwd(), os.environ.get('NAVLIB_X'), sys.path[:3])"


@pytest.fixture
def server(tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    address = str(tmp_path / "fork.sock")
    process = kernel_fork.start(address)
    assert kernel_fork.wait_ready(address, process)
    yield address, process.pid
    process.kill()
    process.wait()


def executed(address, env, cwd):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(CELL)])
    client = nbclient.NotebookClient(
        nb,
        kernel_name="python3",
        timeout=60,
        shutdown_kernel="immediate",
        kernel_manager_class=kernel_fork.manager_class(address),
        resources={"metadata": {"path": str(cwd)}},
    )
    client.execute(env=env)
    pid, parent, folder, setting, path = nb.cells[0].outputs[0]["text"].split(" ", 4)
    return int(pid), int(parent), folder, setting, path


def test_a_forked_kernel_is_a_new_process_with_the_notebooks_environment_and_folder(server, tmp_path):
    address, server_pid = server
    env = dict(os.environ) | {"NAVLIB_X": "forked"}
    first = executed(address, env, tmp_path)
    second = executed(address, env, tmp_path)
    plain = executed(None, env, tmp_path)  # started from nothing
    assert first[1] == second[1] == server_pid and plain[1] == os.getpid()
    assert len({first[0], second[0], server_pid}) == 3  # a new process per notebook
    assert first[2:] == second[2:] == plain[2:] == (str(tmp_path), "forked", plain[4])  # folder, setting, sys.path


def test_another_environment_gets_a_kernel_started_from_nothing(server, tmp_path):
    address, server_pid = server
    assert not kernel_fork.fork_ready(address, dict(os.environ) | {"MPLBACKEND": "module://other"})
    assert kernel_fork.fork_ready(address, dict(os.environ) | {"NAVLIB_TEACHING": "1"})
    assert executed(address, dict(os.environ) | {"MPLBACKEND": "pdf"}, tmp_path)[1] == os.getpid()


def test_a_failed_server_is_not_waited_for(tmp_path):
    address = str(tmp_path / "fork.sock")
    Path(address + ".failed").touch()
    assert not kernel_fork.fork_ready(address, dict(os.environ))
