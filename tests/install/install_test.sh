#!/usr/bin/env bash
# The installed oracle as another project uses it: `cmake --install` into a fresh prefix, then a
# consumer project built against it twice, with find_package(vt CONFIG) and with pkg-config,
# each run over captures that `vt fly --capture` wrote.
#   install_test.sh BUILD_DIR SOURCE_DIR VT_EXECUTABLE WORK_DIR
set -euo pipefail
build=$1 source=$2 vt=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for file in include/vt/oracle.h include/vt/oracle/capture.h lib/cmake/vt/vtConfig.cmake \
  lib/pkgconfig/vt.pc; do
  [[ -f "$prefix/$file" ]] || { echo "not installed: $file" >&2; exit 1; }
done

# Captures of a flight with a small, evicting cache, drawn by the oracle (no GL needed here).
oiiotool --pattern checker:width=16:height=16:color1=1,0.3,0.1:color2=0.1,0.4,1 256x256 3 \
  -o "$work/image.png"
"$vt" build "$work/image.png" -o "$work/t.vt" --page-size 32 --border 2 -q
"$vt" fly "$work/t.vt" --size 96x64 --budget 4 --cache-frames 5 --capture "$work/captures" \
  --capture-every 10 -o "$work/fly" > /dev/null

echo "== find_package(vt CONFIG)"
cmake -S "$source/tests/install/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" > "$work/consumer-configure.log"
cmake --build "$work/consumer" > "$work/consumer-build.log"
"$work/consumer/consumer" "$work/captures"

echo "== pkg-config vt"
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
read -r -a flags <<< "$(pkg-config --cflags --libs vt)"
c++ "$source/tests/install/consumer/consumer.cpp" "${flags[@]}" -Wl,-rpath,"$prefix/lib" \
  -o "$work/consumer-pkg-config"
"$work/consumer-pkg-config" "$work/captures"
