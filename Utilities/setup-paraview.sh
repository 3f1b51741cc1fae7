#!/usr/bin/env bash
# Builds the vtkSAVR ParaView plugin (ParaView/) into ./build-paraview on Debian 12 (ParaView
# 5.11, Qt 5) or Debian 13 (ParaView 5.13, Qt 6), as root. ParaView's version, its CMake config
# directory, its Python's version and the Qt major version it was built with are read from what
# is installed.
#
# ParaView's Python (python3-paraview) conflicts with python3-vtk9, which libvtk9-dev (the
# standalone build) needs. So python3-paraview is never installed: its package is unpacked into
# build-paraview/python3-paraview, and ParaView's CMake config directory is copied to
# build-paraview/paraview-config with its paths rewritten to point there (ParaView's config checks
# that its Python modules, pvpython and the wrapping hierarchy files exist).
# Run pvbatch with PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages.
#
# Idempotent: packages already present are not installed again, the unpack and the rewritten
# config are redone only when ParaView's version changes, the build is incremental.
# Environment: SAVR_PARAVIEW_JOBS (default 2) build jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build-paraview"
jobs=${SAVR_PARAVIEW_JOBS:-2}
export DEBIAN_FRONTEND=noninteractive

install_missing() {
  local p missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup-paraview: installing ${missing[*]}"
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
}

install_missing build-essential cmake python3-dev libtbb-dev libeigen3-dev xvfb xauth \
  mricron-data libvtk9-dev python3-vtk9 paraview paraview-dev openmpi-bin
if dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  echo "setup-paraview: note: python3-paraview is installed system-wide; the private copy is used anyway"
fi

# ParaView's CMake config directory, from paraview-dev's own file list, and the Qt it was built
# with: 5.13's config says PARAVIEW_QT_MAJOR_VERSION; 5.11's names Qt5 targets.
pvcmake=$(dirname "$(dpkg -L paraview-dev | grep -m 1 '/cmake/paraview-[0-9.]*/paraview-config.cmake$')")
[ -f "$pvcmake/paraview-config.cmake" ] || { echo "setup-paraview: no paraview-config.cmake in paraview-dev" >&2; exit 1; }
qt=$(sed -n 's/^set(PARAVIEW_QT_MAJOR_VERSION "\{0,1\}\([0-9]*\).*/\1/p' "$pvcmake/paraview-config.cmake" | head -n 1)
if [ -z "$qt" ] && grep -q -r 'Qt5::' "$pvcmake"; then qt=5; fi
case "$qt" in
  5) install_missing qtbase5-dev libqt5svg5-dev libqt5opengl5-dev qttools5-dev ;;
  6) install_missing qt6-base-dev qt6-svg-dev qt6-tools-dev qt6-5compat-dev ;;
  *) echo "setup-paraview: cannot tell which Qt ParaView uses (from $pvcmake)" >&2; exit 1 ;;
esac
echo "setup-paraview: ParaView config $pvcmake, Qt $qt"

version=$(dpkg-query -W -f='${Version}' paraview)
arch=$(basename "$(dirname "$(dirname "$pvcmake")")")
mkdir -p "$build"

# 1. ParaView's Python, unpacked privately (same version as the installed paraview package).
private="$build/python3-paraview"
if [ "$(cat "$private.version" 2>/dev/null)" != "$version" ]; then
  echo "setup-paraview: unpacking python3-paraview $version into $private"
  rm -rf "$private" "$build"/python3-paraview_*.deb
  # (As root, apt-get download warns that it runs unsandboxed; the download still happens.)
  if ! (cd "$build" && apt-get download -q "python3-paraview=$version"); then
    apt-get update -qq
    (cd "$build" && apt-get download -q "python3-paraview=$version")
  fi
  deb=$(ls "$build"/python3-paraview_*.deb)
  dpkg -x "$deb" "$private"
  rm -f "$deb"
  # ParaView's CMake config may name each Python module X.so (Debian 13's does) while the
  # package ships X.cpython-3NN-<arch>.so: give each module its plain name too.
  find "$private" -name '*.cpython-*.so' -type f | while read -r f; do
    plain="${f%%.cpython-*}.so"
    [ -e "$plain" ] || ln -s "$(basename "$f")" "$plain"
  done
  echo "$version" > "$private.version"
fi
dist="$private/usr/lib/python3/dist-packages"
hierarchy="$private/usr/lib/$arch/vtk/hierarchy"
[ -d "$dist/paraview" ] && [ -d "$hierarchy/ParaView" ] && compgen -G "$private/usr/bin/pvpython*" >/dev/null ||
  { echo "setup-paraview: the private python3-paraview in $private is incomplete" >&2; exit 1; }

# 2. ParaView's CMake config, rewritten to use the private Python and absolute /usr paths.
config="$build/paraview-config/$(basename "$pvcmake")"
stamp="$version $dist"
if [ "$(cat "$config.stamp" 2>/dev/null)" != "$stamp" ]; then
  echo "setup-paraview: writing a rewritten copy of $pvcmake to $config"
  rm -rf "$config"
  mkdir -p "$(dirname "$config")"
  cp -a "$pvcmake" "$config"
  # The copy lives elsewhere, so every path computed from the config's own location is made
  # absolute: Python modules and pvpython from the private unpack, everything else from /usr.
  find "$config" -name '*.cmake' -type f -print0 | xargs -0 sed -i \
    -e "s|\${_IMPORT_PREFIX}/lib/python3/dist-packages|$dist|g" \
    -e "s|\${_IMPORT_PREFIX}/bin/pvpython\"|$private/usr/bin/pvpython\"|g" \
    -e "s|\"/usr/bin/pvpython\"|\"$private/usr/bin/pvpython\"|g" \
    -e "s|\${_IMPORT_PREFIX}|/usr|g" \
    -e "s|\${CMAKE_CURRENT_LIST_DIR}/../../../../../../|/usr/|g"
  find "$config" -name '*-vtk-module-properties.cmake' -type f -print0 | xargs -0 sed -i \
    -e "s|\${_vtk_module_import_prefix}/lib/$arch/vtk/hierarchy|$hierarchy|g" \
    -e "s|\${_vtk_module_import_prefix}/|/usr/|g"
  echo 'set(_vtk_module_import_prefix "/usr")' >> "$config/paraview-prefix.cmake"
  echo 'set(_vtk_module_import_prefix "/usr")' >> "$config/vtk/vtk-prefix.cmake"
  echo "$stamp" > "$config.stamp"
fi

# 3. Configure and build the plugin. Debian's /usr/bin/python3 is the interpreter ParaView's
# Python modules belong to, whatever python3 comes first on the PATH.
echo "setup-paraview: configuring ParaView/ into $build (ParaView_DIR=$config)"
cmake -S "$root/ParaView" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DParaView_DIR="$config" -DPython3_EXECUTABLE=/usr/bin/python3
echo "setup-paraview: building with -j$jobs"
cmake --build "$build" -j"$jobs"
plugin=$(find "$build" -name 'SAVRPlugin.so' -path '*/plugins/SAVRPlugin/*' | head -n 1)
echo "setup-paraview: plugin: ${plugin:-not found}"
echo "setup-paraview: run pvbatch with PYTHONPATH=$dist"
