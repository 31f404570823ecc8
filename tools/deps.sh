#!/usr/bin/env bash
# Installs the Debian packages voxgi's tests, tools and examples need to get a headless
# OpenGL 4.5 context, and what the tests build with. Idempotent and silent when everything is
# already there.
#
# Our programs load EGL and OSMesa at run time (tools/headless_gl.h), so the runtime
# libraries are what they need; the -dev packages add the headers and link names for
# programs that bind OSMesa or EGL directly, as an application embedding voxgi may:
#   libegl1          libEGL.so.1, the EGL loader
#   libegl-mesa0     Mesa's EGL vendor, which provides the surfaceless platform
#   libgl1-mesa-dri  the llvmpipe software rasteriser behind EGL
#   libosmesa6       libOSMesa.so.8, the fallback when EGL is unusable
#   libosmesa6-dev, libegl-dev   osmesa.h, EGL/egl.h and the libraries to link against
# the C++ compiler the tests build the header with (g++; the C compiler comes with it), and
#   libgmp-dev       GMP's rationals, in which tests/test_exact.c's oracle decides exactly
#   python3-numpy    numpy.load, the independent reader of the .npy exports (tests/test_io_export.c)
#   libglfw3-dev     GLFW's header and library, for the windowed viewer (examples/viewer.c)
#   xvfb, xauth      a virtual X server (and the cookie xvfb-run hands it) in which the viewer's
#                    test opens its window headless
#
# `bash tools/deps.sh fuzz` installs instead what `make fuzz` builds its harnesses with (fuzz/):
#   clang               the compiler whose -fsanitize=fuzzer instruments and links libFuzzer
#   libclang-rt-14-dev  clang's runtimes: libFuzzer's driver, ASan and UBSan
#   libfuzzer-14-dev    libFuzzer as a library, for linking a harness outside clang's driver
set -euo pipefail

case "${1:-}" in
    "") packages=(libegl1 libegl-mesa0 libgl1-mesa-dri libosmesa6 libosmesa6-dev libegl-dev g++ libgmp-dev python3-numpy libglfw3-dev xvfb xauth) ;;
    fuzz) packages=(clang libclang-rt-14-dev libfuzzer-14-dev) ;;
    *) echo "usage: bash tools/deps.sh [fuzz]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
    # The status, as dpkg -s shows it: a removed but not purged package still has an entry.
    [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" = "install ok installed" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
    as_root=()
elif command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
else
    echo "deps.sh: need root or sudo to install: ${missing[*]}" >&2
    exit 1
fi

# sudo resets the environment, so the settings go through env.
# DPkg::Lock::Timeout: wait up to 10 minutes for another apt or dpkg (an unattended upgrade) to let go of
# its lock instead of failing at once.
apt_get() { "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive DEBCONF_NOWARNINGS=yes apt-get -qq -o DPkg::Lock::Timeout=600 "$@"; }

echo "deps.sh: installing ${missing[*]}"
apt_get update
apt_get install -y --no-install-recommends "${missing[@]}" >/dev/null
echo "deps.sh: done"
