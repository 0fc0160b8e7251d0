"""Private network namespaces for GigE Vision work that must not leave the machine (the project's network rule).

GigE Vision discovery broadcasts on every interface, and a fake GigE camera answers on the network it is
given. Tests and benchmarks run such code in a fresh network namespace that has only a loopback interface:
``unshare -n sh -c 'ip link set lo up && exec CMD'`` (needs root, or unprivileged user namespaces with
``unshare -rn``). Inside, nothing can reach any other host.
"""

from __future__ import annotations

import functools
import os
import shlex
import shutil
import socket
import subprocess


def in_private_netns() -> bool:
    """True when this process sees no network interface but loopback."""
    return {name for _, name in socket.if_nameindex()} <= {"lo"}


def _unshare_prefix() -> list[str]:
    return ["unshare", "-n"] if os.geteuid() == 0 else ["unshare", "-rn"]


@functools.cache
def netns_unavailable_reason() -> str | None:
    """None when a private network namespace can be made here, else why not (for a skip message)."""
    for tool in ("unshare", "ip"):
        if shutil.which(tool) is None:
            return f"'{tool}' is not installed"
    try:
        r = subprocess.run([*_unshare_prefix(), "sh", "-c", "ip link set lo up"], capture_output=True, text=True,
                           timeout=10)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"unshare failed: {exc}"
    if r.returncode != 0:
        return f"cannot create a network namespace ({' '.join(_unshare_prefix())}): {r.stderr.strip()}"
    return None


def netns_command(argv: list[str]) -> list[str]:
    """``argv`` wrapped to run in a new private network namespace with loopback up."""
    return [*_unshare_prefix(), "sh", "-c", "ip link set lo up && exec " + shlex.join(argv)]


def start_fake_gv_camera(serial: str, loss_per_mille: int = 0) -> subprocess.Popen[bytes]:
    """Aravis's fake GigE Vision camera (``arv-fake-gv-camera-0.8``) serving on 127.0.0.1, with ``loss_per_mille``
    GVSP packets dropped; refused outside a private network namespace (the network rule). Given 0.3 s to bind."""
    import time

    if not in_private_netns():
        raise RuntimeError("the fake GigE Vision camera runs only inside a private network namespace (netns_command)")
    argv = ["arv-fake-gv-camera-0.8", "-i", "127.0.0.1", "-s", serial]
    if loss_per_mille:
        argv += ["-r", str(loss_per_mille)]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(0.3)
    return proc
