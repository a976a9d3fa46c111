#!/usr/bin/env bash
# Installs what luxtrace needs from Debian 12's packages (run as root). Does nothing
# when everything is already there.
set -euo pipefail
packages=(
  build-essential cmake git pkg-config
  libembree-dev libtbb-dev libopenmpi-dev openmpi-bin libhdf5-dev hdf5-tools
  libcli11-dev libglm-dev libgtest-dev
  libtomlplusplus-dev libassimp-dev librandom123-dev libboost-dev
  python3-h5py python3-numpy python3-matplotlib python3-pytest python3-setuptools
  slurm-wlm munge
  libcairo2-dev libopenexr-dev fonts-dejavu-core   # render (LUXTRACE_RENDER; cairo brings libpng)
  libxml2-utils                 # xmllint: the XDMF companions in the tests
  clang-14 libclang-rt-14-dev   # the libFuzzer build (tests/fuzz/README.md)
  clang-format-14               # scripts/check_format.sh (.clang-format)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then echo "need root to install packages (or install them yourself)" >&2; exit 1; fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
