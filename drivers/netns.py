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
