"""Notebook kernels forked from one process that has already imported the scientific stack (for tools/reproduce.py).

Each executed notebook gets its own kernel process, as before: a new process with a new interpreter state in
which no notebook code has run. Only its start differs. Instead of ``python -m ipykernel_launcher -f CONN``
starting from nothing (~0.7 s of CPU per kernel, then ~1 s per notebook for the imports of its first cell),
:func:`serve` imports ipykernel and the third-party packages the notebooks import (:data:`PRELOAD`; never
navlib, which reads per-notebook settings at import) once, and forks a kernel per request: the child sets the
notebook's environment, working directory and standard streams, then runs ipykernel's own entry point with the
same arguments. :class:`ForkingKernelManager` is the kernel manager nbclient uses for it; the kernel's process id
is the child's, so the runner reads its CPU time and memory as before. Besides the imports, the server does what
numba does on the first call of any compiled function in a process (its registries; no navlib kernel is loaded).

The server is started with the runner's environment (:func:`start`), which the kernels also get apart from their
``NAVLIB_*`` settings: packages read their settings (``MPLBACKEND``, ``NUMBA_CACHE_DIR``, thread counts) at import.
:func:`fork_ready` refuses an environment that differs in anything else, and the manager then starts the kernel
the usual way.
"""

from __future__ import annotations

import asyncio
import ctypes
import functools
import json
import os
import signal
import socket
import subprocess
import sys
import time
import uuid
from pathlib import Path

PRELOAD = (
    "ipykernel.kernelapp",
    "numpy",
    "pandas",
    "matplotlib.pyplot",
    "scipy.linalg",
    "scipy.stats",
    "scipy.signal",
    "scipy.integrate",
    "scipy.spatial.transform",
    "numba",
)
"""Imported by the server before it forks: ipykernel and what the notebooks' first cells import (not navlib)."""
PRELOAD_IF_INSTALLED = ("pyproj", "imufusion", "vqf", "ahrs")
"""The peer packages the notebooks compare against (notebooks 03 and 07), where installed."""

SUPPORTED = sys.platform.startswith("linux")
"""Where kernels are forked (measured here). Elsewhere they start the usual way: Windows has no fork, and on macOS a
fork after numpy's Accelerate BLAS or other Objective-C code has started is unsafe."""
KERNEL_MODULE = "ipykernel_launcher"
SAME_FROM_SERVER = ("NAVLIB_",)
"""Environment variables a kernel may have that differ from the server's (read by navlib when it runs, not at import)."""


def _die_with_parent(sig: int = signal.SIGKILL) -> None:
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None).prctl(1, sig)  # PR_SET_PDEATHSIG


# ------------------------------------------------------------------------------------------------- server


def serve(address: str) -> None:
    """Import :data:`PRELOAD`, listen on the Unix socket ``address`` and fork a kernel per request."""
    _die_with_parent(signal.SIGTERM)
    if sys.path and Path(sys.path[0]).resolve() == Path(__file__).resolve().parent:
        del sys.path[0]  # as ipykernel_launcher removes its own folder; the kernel adds the notebook's back
    import importlib

    for name in PRELOAD:
        importlib.import_module(name)
    for name in PRELOAD_IF_INSTALLED:
        try:
            importlib.import_module(name)
        except ImportError:  # the notebook that needs it says so itself
            pass
    from numba.core.registry import cpu_target

    # numba's typing and lowering registries, which the first call of any compiled function installs in each
    # process (~0.3 s, even when the function comes from numba's cache): once here
    cpu_target.typing_context.refresh()
    cpu_target.target_context.refresh()
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # the kernels are reaped by the system
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(address + ".tmp")
    server.listen(8)
    os.rename(address + ".tmp", address)  # appears when ready
    while True:
        conn, _ = server.accept()
        with conn:
            message, fds, _, _ = socket.recv_fds(conn, 1 << 20, 3)
            request = json.loads(message)
            ready_r, ready_w = os.pipe()
            pid = os.fork()
            if pid == 0:
                server.close()
                conn.close()
                os.close(ready_r)
                _become_kernel(request, fds, ready_w)
            os.close(ready_w)
            os.read(ready_r, 1)  # the child is in its own session: its process group can be signalled
            os.close(ready_r)
            for fd in fds:
                os.close(fd)
            conn.sendall(json.dumps({"pid": pid}).encode())


def _become_kernel(request: dict, fds: list[int], ready: int) -> None:
    """In the forked child: the notebook's session, streams, environment and folder; then ipykernel's entry point."""
    status = 1
    try:
        os.setsid()
        _die_with_parent()
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        os.write(ready, b"1")
        os.close(ready)
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        # ipykernel read JPY_PARENT_PID when the server imported it: the parent (this server) is given again
        parent = str(os.getppid())
        os.environ.clear()
        os.environ.update(request["env"] | {"JPY_PARENT_PID": parent})
        os.chdir(request["cwd"])
        sys.argv = [KERNEL_MODULE, *request["args"], f"--IPKernelApp.parent_handle={parent}"]
        from ipykernel import kernelapp

        kernelapp.launch_new_instance()
        status = 0
    finally:
        os._exit(status)


def start(address: str) -> subprocess.Popen:
    """Start the server (with this process's environment) on ``address``; returns at once (:func:`wait_ready`)."""
    return subprocess.Popen(
        [sys.executable, __file__, address], stdin=subprocess.DEVNULL, preexec_fn=lambda: _die_with_parent(signal.SIGTERM)
    )


def wait_ready(address: str, server: subprocess.Popen, timeout: float = 60.0) -> bool:
    """Wait until the server listens; False if it died or took longer than ``timeout``."""
    end = time.monotonic() + timeout
    while not os.path.exists(address):
        if server.poll() is not None or time.monotonic() > end:
            Path(address + ".failed").touch()  # the kernels waiting for it in fork_ready start from nothing
            return False
        time.sleep(0.01)
    return True


# ------------------------------------------------------------------------------------------------- client


def fork_ready(address: str | None, env: dict[str, str]) -> bool:
    """Whether a kernel with environment ``env`` can be forked from the server at ``address``: ``env`` is the
    server's (this process's) apart from the ``NAVLIB_*`` settings, and the server listens (waited for while it
    imports, unless :func:`wait_ready` found that it failed)."""
    keys = set(env) | set(os.environ)
    if not address or any(env.get(k) != os.environ.get(k) for k in keys if not k.startswith(SAME_FROM_SERVER)):
        return False
    while not os.path.exists(address):
        if os.path.exists(address + ".failed"):
            return False
        time.sleep(0.01)
    return True


class ForkedKernel:
    """The part of :class:`subprocess.Popen` that jupyter_client uses, for a kernel forked by the server (not a child of
    this process: its exit status is not known, only whether it runs)."""

    stdin = stdout = stderr = None

    def __init__(self, pid: int) -> None:
        self.pid = pid
        self.returncode: int | None = None

    def poll(self) -> int | None:
        if self.returncode is None:
            try:
                os.kill(self.pid, 0)
            except ProcessLookupError:
                self.returncode = 0
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        end = None if timeout is None else time.monotonic() + timeout
        while self.poll() is None:
            if end is not None and time.monotonic() > end:
                raise subprocess.TimeoutExpired(KERNEL_MODULE, timeout)
            time.sleep(0.01)
        return self.returncode or 0

    def send_signal(self, sig: int) -> None:
        if self.poll() is None:
            os.kill(self.pid, sig)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)

    def terminate(self) -> None:
        self.send_signal(signal.SIGTERM)


def _forking_manager():
    from queue import Empty

    from jupyter_client import AsyncKernelManager
    from jupyter_client.asynchronous.client import AsyncKernelClient
    from jupyter_client.provisioning import LocalProvisioner
    from traitlets import default

    class ForkingProvisioner(LocalProvisioner):
        """Launches the kernel command ``python -m ipykernel_launcher ARGS`` by a fork of the server."""

        address: str = ""

        async def launch_kernel(self, cmd: list[str], **kwargs):
            args = _kernel_args(cmd)
            env = kwargs.get("env") or dict(os.environ)
            if args is None or not fork_ready(self.address, env):
                return await super().launch_kernel(cmd, **kwargs)
            streams = [kwargs.get("stdin"), kwargs.get("stdout"), kwargs.get("stderr")]
            with open(os.devnull, "rb") as devnull:
                fds = [_fileno(s, default) for s, default in zip(streams, (devnull.fileno(), 1, 2), strict=True)]
                request = {"args": args, "env": env, "cwd": str(kwargs.get("cwd") or os.getcwd())}
                with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as conn:
                    conn.connect(self.address)
                    socket.send_fds(conn, [json.dumps(request).encode()], fds)
                    pid = json.loads(conn.recv(1 << 16))["pid"]
            self.process = ForkedKernel(pid)
            self.pid = self.pgid = pid
            self.cwd = request["cwd"]
            return self.connection_info

        async def wait(self):
            """Until the kernel has ended: polled every 10 ms (jupyter_client's every 100 ms)."""
            while self.process is not None and self.process.poll() is None:
                await asyncio.sleep(0.01)
            self.process = None
            return 0

    class QuickClient(AsyncKernelClient):
        """jupyter_client's client, ready once the kernel has answered and IOPub has been quiet for 10 ms (200 ms in
        jupyter_client: the idle status of the kernel-info request; the notebook's cells never wait for messages
        that are not theirs)."""

        async def _async_wait_for_ready(self, timeout=None):
            deadline = time.monotonic() + (float("inf") if timeout is None else timeout)
            while True:
                self.kernel_info()
                try:
                    msg = await self.shell_channel.get_msg(timeout=1)
                    if msg["msg_type"] == "kernel_info_reply":
                        await self.iopub_channel.get_msg(timeout=0.2)  # IOPub is connected
                        self._handle_kernel_info_reply(msg)
                        break
                except Empty:
                    pass
                if not await self._async_is_alive():
                    raise RuntimeError("Kernel died before replying to kernel_info")
                if time.monotonic() > deadline:
                    raise RuntimeError(f"Kernel didn't respond in {timeout:g} seconds")
            try:
                while True:
                    await self.iopub_channel.get_msg(timeout=0.01)
            except Empty:
                pass

    class ForkingKernelManager(AsyncKernelManager):
        """nbclient's kernel manager with the kernel forked from the server at :attr:`address` (when it can be)."""

        address: str = ""

        @default("client_factory")
        def _quick_client(self):
            return QuickClient

        async def _async_wait(self, pollinterval: float = 0.01) -> None:
            """Until the killed kernel has ended: polled every 10 ms (jupyter_client's every 100 ms)."""
            await super()._async_wait(pollinterval=0.01)

        async def _async_pre_start_kernel(self, **kw):
            if self.provisioner is None:
                self.kernel_id = self.kernel_id or kw.pop("kernel_id", None) or uuid.uuid4().hex
                self.provisioner = ForkingProvisioner(kernel_id=self.kernel_id, kernel_spec=self.kernel_spec, parent=self)
                self.provisioner.address = self.address
            return await super()._async_pre_start_kernel(**kw)

    return ForkingKernelManager


@functools.cache
def manager_class(address: str | None):
    """A kernel manager class for nbclient whose kernels are forked from the server at ``address`` (built once per
    address and process)."""
    cls = _forking_manager()
    return type("ForkingKernelManager", (cls,), {"address": address or ""})


def _kernel_args(cmd: list[str]) -> list[str] | None:
    """The arguments after ``python -m ipykernel_launcher`` in a kernel command of this interpreter, else None."""
    if len(cmd) >= 3 and cmd[1:3] == ["-m", KERNEL_MODULE] and os.path.realpath(cmd[0]) == os.path.realpath(sys.executable):
        return cmd[3:]
    return None


def _fileno(stream, default: int) -> int:
    if stream is None or stream == subprocess.PIPE:
        return default
    return stream if isinstance(stream, int) else stream.fileno()


if __name__ == "__main__":
    serve(sys.argv[1])
