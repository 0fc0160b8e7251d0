#!/usr/bin/env bash
# Installs the Debian packages the station needs, only those missing (a second run takes well under a second).
#   libllvm19                    Mitsuba's LLVM variants (LLVM 14/15 on Debian 12 are too old or crash)
#   gir1.2-aravis-0.8 ...        Aravis (GenICam) for PyGObject, and arv-fake-gv-camera-0.8 for tests
#   libgirepository1.0-dev ...   to build PyGObject<3.52 from PyPI
#   socat                        pty pairs for the serial tests
#   iproute2 util-linux          private network namespaces for GigE Vision tests (unshare, ip)
set -euo pipefail
pkgs=(libllvm19 gir1.2-aravis-0.8 libaravis-0.8-0 aravis-tools libgirepository1.0-dev libcairo2-dev
      pkg-config socat iproute2 util-linux)
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "installing Debian packages: ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
