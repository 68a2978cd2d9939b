#!/usr/bin/env bash
# Two hosts, verified (issue 18 item 11): the robot (network namespace A:
# lcm-logplayer as the camera, stairs-perception) and the operator's machine
# (namespace B: stairs-tracker, lcm-logger) joined by a veth pair, multicast
# with ttl=1 as README's two-machine setup says. Every depth frame sent on A
# must give an observation on A and a model on B, nothing lost; the recording
# made on B is scored with stairs-eval --recorded.
#   test_two_hosts.sh BUILD_DIR SOURCE_DIR       (root; exit 77 = skipped)
set -euo pipefail
build=$1 src=$2
bin=$build/bin
if [ "$(id -u)" != 0 ]; then echo "skipped: network namespaces need root"; exit 77; fi
tag=$$
a=stairs_a_$tag b=stairs_b_$tag
tmp=$(mktemp -d)
cleanup() {
  ip netns pids "$a" 2>/dev/null | xargs -r kill 2>/dev/null || true
  ip netns pids "$b" 2>/dev/null | xargs -r kill 2>/dev/null || true
  sleep 0.2
  ip netns del "$a" 2>/dev/null || true
  ip netns del "$b" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT
if ! ip netns add "$a" 2>/dev/null; then echo "skipped: cannot create network namespaces here"; exit 77; fi
ip netns add "$b"
ip link add "va$tag" type veth peer name "vb$tag"
ip link set "va$tag" netns "$a"
ip link set "vb$tag" netns "$b"
for ns in "$a:va$tag:10.231.0.1" "$b:vb$tag:10.231.0.2"; do
  IFS=: read -r n dev addr <<<"$ns"
  ip -n "$n" link set lo up
  ip -n "$n" addr add "$addr/24" dev "$dev"
  ip -n "$n" link set "$dev" up multicast on
  ip -n "$n" route add 224.0.0.0/4 dev "$dev"
done
url='udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304'
log=$src/logs/up_handheld.lcmlog

# Operator (B): the tracker and the recorder.
ip netns exec "$b" "$bin/stairs-tracker" --lcm-url "$url" 2>"$tmp/tracker.err" &
ip netns exec "$b" lcm-logger --quiet --lcm-url="$url" "$tmp/b.lcmlog" &
# Robot (A): perception, then the camera (a log played at its frame rate).
ip netns exec "$a" "$bin/stairs-perception" --lcm-url "$url" 2>"$tmp/perception.err" &
sleep 1
ip netns exec "$a" lcm-logplayer --lcm-url="$url" "$log" >/dev/null
sleep 1.5
ip netns pids "$a" | xargs -r kill -TERM
ip netns pids "$b" | xargs -r kill -TERM
wait || true
cat "$tmp/perception.err" "$tmp/tracker.err"

"$bin/stairs-eval" --recorded "$tmp/b.lcmlog" --json "$tmp/b.json" --quiet
/usr/bin/python3 - "$tmp/b.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
rec, n = r["recorded"], r["frames_processed"]
print(f"operator's recording: {n} depth frames, {rec['observations']} observations, {rec['models']} models, "
      f"{rec['frames_without_observation']} frames without an observation")
ok = n == 90 and rec["observations"] == n and rec["models"] == n and rec["frames_without_observation"] == 0 \
     and rec["rejected_messages"] == 0 and r["score"]["model_steps_detected"] == r["score"]["model_steps_real"]
sys.exit(0 if ok else 1)
PY
grep -q "90 received, 90 published, 0 dropped" "$tmp/tracker.err" || { echo "the tracker lost observations"; exit 1; }
echo "two hosts: every frame crossed, nothing lost"
