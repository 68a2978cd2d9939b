#!/usr/bin/env bash
# cmake --install to a prefix as a new user would use it (issue 18 item 7/8):
# another CMake project finds the types with find_package(stairs), pkg-config
# finds them too, and the installed stairs-launch and stairs-model-csv run a
# log through the live chain and write its model to CSV and a plot.
#   test_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null

echo "== find_package(stairs) from another project"
cmake -S "$src/tests/install/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/consumer" >/dev/null
hash=$("$tmp/consumer/consumer")
[ -n "$hash" ] || { echo "consumer printed no fingerprint"; exit 1; }
echo "consumer decoded its model (fingerprint $hash)"

echo "== pkg-config stairs"
flags=$(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags stairs)
case "$flags" in *"$prefix/lib/pkgconfig/../../include"*) ;; *) echo "pkg-config --cflags stairs gave '$flags'"; exit 1 ;; esac
c++ -std=c++11 $flags "$src/tests/install/consumer/main.cpp" -o "$tmp/consumer_pc" \
  $(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --libs stairs)
[ "$("$tmp/consumer_pc")" = "$hash" ] || { echo "pkg-config build differs"; exit 1; }
echo "built with pkg-config: same fingerprint"

echo "== the installed programs: stairs-launch, then stairs-model-csv"
"$prefix/bin/stairs-perception" --version
[ "$(id -u)" != 0 ] || ip route add 224.0.0.0/4 dev lo 2>/dev/null || true
env -u BUILD_DIR "$prefix/bin/stairs-launch" --log "$src/logs/down_handheld.lcmlog" \
  --lcm-url 'udpm://239.255.76.67:7687?ttl=0&recv_buf_size=4194304' --record "$tmp/run.lcmlog"
env -u BUILD_DIR /usr/bin/python3 "$prefix/bin/stairs-model-csv" "$tmp/run.lcmlog" --plot "$tmp/run.png"
rows=$(($(wc -l < "$tmp/run.model.csv") - 1))
steps=$(($(wc -l < "$tmp/run.steps.csv") - 1))
echo "CSV: $rows models, $steps steps in the final model"
[ "$rows" -gt 0 ] && [ "$steps" -gt 0 ] && [ -s "$tmp/run.png" ] || { echo "no models, steps or plot"; exit 1; }
grep -q "ExecStart=$prefix/bin/stairs-perception" "$prefix/lib/systemd/system/stairs-perception.service" \
  || { echo "systemd unit does not name the installed program"; exit 1; }
grep -q "EnvironmentFile=-$prefix/etc/default/stairs" "$prefix/lib/systemd/system/stairs-tracker.service" \
  || { echo "systemd unit does not name the installed environment file"; exit 1; }
echo "install test passed"
