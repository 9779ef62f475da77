#!/usr/bin/env bash
# tools/setup.sh: installs what affray needs to build and test on Debian 12, from Debian's own
# packages. Idempotent, and silent when everything is already there.
set -euo pipefail

packages=(build-essential cmake flex bison libopenexr-dev libglm-dev zlib1g-dev catch2
          libmcpp-dev openimageio-tools libopenimageio-dev clang-format-14 clang-14 libclang-rt-14-dev
          slurm-wlm munge)

missing=()
for p in "${packages[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "affray setup: installing ${missing[*]}" >&2
sudo=""
if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "affray setup: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
