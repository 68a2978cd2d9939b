#!/usr/bin/env bash
# The .deb (issue 18 item 7) as apt would install it: its dependencies name the
# shared libraries the programs need, the systemd units name /usr/bin, the
# environment file is a conffile, and the unpacked programs run.
#   test_deb.sh BUILD_DIR
set -euo pipefail
build=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$build" && cpack -G DEB -B "$tmp" >/dev/null)
deb=$(ls "$tmp"/stairs_*.deb)
dpkg-deb -I "$deb" control > "$tmp/control"
for dep in liblcm1 liblcm-bin python3 libpcl-common libopencv-core libopenni2-0; do
  grep -q "^Depends:.*$dep" "$tmp/control" || { echo "Depends lacks $dep:"; cat "$tmp/control"; exit 1; }
done
dpkg-deb -I "$deb" conffiles | grep -qx /etc/default/stairs || { echo "/etc/default/stairs is no conffile"; exit 1; }
dpkg-deb -x "$deb" "$tmp/root"
for f in usr/bin/stairs-perception usr/bin/stairs-tracker usr/bin/stairs-launch usr/bin/stairs-model-csv \
         usr/include/stairs/stair_model_t.hpp usr/lib/cmake/stairs/stairsConfig.cmake usr/lib/pkgconfig/stairs.pc \
         usr/lib/python3/dist-packages/stairs/stair_model_t.py usr/lib/python3/dist-packages/stairs_lcmlog.py \
         usr/share/java/stairs_lcmtypes.jar usr/share/stairs/lcmtypes/stair_model_t.lcm etc/default/stairs; do
  [ -e "$tmp/root/$f" ] || { echo "the .deb lacks /$f"; exit 1; }
done
grep -qx 'ExecStart=/usr/bin/stairs-tracker $STAIRS_TRACKER_ARGS' "$tmp/root/usr/lib/systemd/system/stairs-tracker.service" \
  || { echo "stairs-tracker.service does not start /usr/bin/stairs-tracker"; exit 1; }
grep -qx 'EnvironmentFile=-/etc/default/stairs' "$tmp/root/usr/lib/systemd/system/stairs-perception.service" \
  || { echo "stairs-perception.service does not read /etc/default/stairs"; exit 1; }
"$tmp/root/usr/bin/stairs-perception" --version
"$tmp/root/usr/bin/stairs-launch" --help | head -1
echo "deb test passed: $(basename "$deb")"
