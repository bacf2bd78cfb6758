#!/bin/bash
# Usage: limits.sh HW3_BINARY — re-runs the cases of unbounded work, silently wrong numbers, torn writes and wrong file kinds; prints exit, stderr, what was written.
# Needs a 64 KiB tmpfs for the full-disk cases: mkdir -p /tmp/hostile_tiny && mount -t tmpfs -o size=64k tmpfs /tmp/hostile_tiny
B=$(realpath "${1:?binary}"); ROOT=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p /tmp/hostile_repro; W=$(mktemp -d /tmp/hostile_repro/run.XXXX); cd "$W"
run(){ echo "\$ hw3 $*" | cut -c1-160; timeout ${T:-10} "$B" "$@" > out.txt 2> err.txt; local rc=$?; echo "  exit $rc; stdout $(wc -c <out.txt) B: $(head -c 200 out.txt | tr '\n' '|' | cat -v)"; echo "  stderr $(wc -c <err.txt) B, $(wc -l <err.txt) lines: $(head -c 300 err.txt | tr '\n' '|' | cat -v)"; }
echo "## 1 unbounded sizes"
run irradiance --env sky --normal 0,0,1 --method sh9 --size 1000000000
(ulimit -v 4000000; run irradiance --env sky --normal 0,0,1 --method sh9 --size 100000)
(ulimit -v 4000000; T=5 run irradiance --env sky --normal 0,0,1 --method sh9 --size 18446744073709551615)
echo "## 2 silently wrong numbers"
for o in -1e16 -1e18 -1e20; do run sphere --origin $o,0,0 --dir 1,0,0 --center 0,0,0 --radius 1 --json; done
run sphere --origin -1e16,0,0 --dir 1,0,0 --center 0,0,0 --radius 1
run sphere --origin 0,0,0 --dir 1,0,0 --center 0,0,0 --radius 1e300 --method naive --json
run sphere --origin 0,0,0 --dir 1,0,0 --center 0,0,0 --radius 1.4e154 --json
run sphere --origin 0,0,0 --dir 1,0,0 --center 0,0,0 --radius 1e200 --json
run sphere --origin 0,0,0 --dir 1,0,0 --center 0,0,0 --radius 1e20 --precision f32 --json
run sphere --origin -1e20,0,0 --dir 1,0,0 --center 0,0,0 --radius 1 --method naive --json
echo "## 3 atomic writes (64 KiB tmpfs at /tmp/hostile_tiny)"
rm -rf /tmp/hostile_tiny/*; $B render still --spp 1 --size 16x16 --out /tmp/hostile_tiny/good.png 2>/dev/null; echo "  good.png before: $(wc -c < /tmp/hostile_tiny/good.png) B"
dd if=/dev/zero of=/tmp/hostile_tiny/filler bs=1k count=58 2>/dev/null
run render still --spp 1 --size 200x200 --out /tmp/hostile_tiny/good.png
echo "  good.png after: $(wc -c < /tmp/hostile_tiny/good.png) B, IEND: $(tail -c 8 /tmp/hostile_tiny/good.png | grep -c IEND); dir: $(ls /tmp/hostile_tiny | tr '\n' ' ')"
rm -f /tmp/hostile_tiny/filler /tmp/hostile_tiny/good.png
T=120 run figures --out /tmp/hostile_tiny/figs
echo "  figs written: $(ls /tmp/hostile_tiny/figs 2>/dev/null | wc -l) files; leftovers: $(ls -a /tmp/hostile_tiny/figs 2>/dev/null | grep -c '^\.hw3')"; rm -rf /tmp/hostile_tiny/*
echo "## 4 stdout to /dev/full"
for c in scenes answers template "sphere --origin -5,1,0 --dir 1,0,0 --center 0,0,0 --radius 2" "kd-trace --origin 5,0 --dir -1,1" "effects fog" effects-table; do
  timeout 20 $B $c > /dev/full 2> err.txt; echo "\$ hw3 $c > /dev/full: exit $?; stderr: $(head -c 200 err.txt | tr '\n' '|')"; done
template_file=$W/t.toml; $B template --seed 7 > $template_file
timeout 20 $B check $template_file > /dev/full 2> err.txt; echo "\$ hw3 check t.toml > /dev/full: exit $?; stderr: $(head -c 200 err.txt | tr '\n' '|')"
echo "## 5 work without bound"
T=3 run irradiance --env sky --normal 0,0,1 --method uniform --samples 1000000000000
T=3 run render still --size 4096x4096 --spp 65536 --out big.png
(ulimit -v 4000000; T=10 run check /dev/zero)
python3 -c "
import random
print('[meta]\nseed = 0')
for i in range(1700000): print(f'k{i} = {i}')" > keys.toml
echo "  keys.toml: $(wc -c < keys.toml) B"
T=120 run check keys.toml
echo "## 6 checked too late"
T=200 run render fog --size 1024x768 --spp 16 --out /nonexistent/dir/x.png
T=200 run render fog --size 2048x2048 --spp 1 --out /nonexistent/dir/x.png
touch afile; T=100 run figures --out afile
echo "## 7 round trips"
$B template --seed 9223372036854775808 > big_seed.toml; echo "  template --seed 2^63: exit $?"; run check big_seed.toml
run template --seed 18446744073709551616
echo "## 8 wrong shapes"
printf 'meta = 3\nq2a.t = 1.0\n' > meta3.toml; run check meta3.toml
printf 'meta = [1,2,3]\nq2a.t = 1.0\n' > meta_arr.toml; run check meta_arr.toml
echo "## 9 wrong files"
cp "$ROOT"/docs/figures/q1_clutter.png fake.hdr; run irradiance --env fake.hdr --normal 0,0,1 --method sh9
python3 - <<'PY'
open('one.hdr','wb').write(b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n' + bytes([128,128,128,129]))
PY
for m in unweighted weighted uniform cosine map mis sh9; do run irradiance --env one.hdr --normal 0,0,1 --method $m --json; done
echo "## 10 one line"
run answers --bogus
run template --seed -1
run sphere --origin -5,1,0 --dir 1,0,0 --center 0,0,0 --radius 2 --json
run sphere --origin=-5,1,0 --dir 1,0,0 --center 0,0,0 --radius 2 --json
run sphere --origin -5 --dir 1,0,0 --center 0,0,0 --radius 2
run render still --spp -1
run sphere --origin -5,1,0 --dir 1,0,0 --center 0,0,0 --radius -2
echo "## 11 smaller"
run irradiance --env sky --normal 0,0,1 --method foo
$B sphere --help | grep -A1 -i radius | head -3
run render still --spp 1 --size 8x8 --out image.jpg; echo "  image.jpg magic: $(head -c 4 image.jpg 2>/dev/null | od -An -c | tr -s ' ')"
printf '[meta]\nseed = 0\n[q2a]\nt = "\033[31mRED\033[0m\\u001b[2J"\n' > esc.toml; run check esc.toml
printf '[meta]\nseed = 0\n[q3d]\nleaves = "\\u001b[2J\\u0007 x>=3"\n' > esc2.toml; run check esc2.toml
python3 -c "print('[meta]\nseed = 0\n[q2a]\nt = \"' + 'x'*5000000 + '\"')" > huge.toml; run check huge.toml
python3 -c "print('[meta]\nseed = 0\n[q2a]\nt = ' + '1'*5000000)" > huge2.toml; run check huge2.toml
run sphere --origin "$(python3 -c "print('1'*100000)")" --dir 1,0,0 --center 0,0,0 --radius 1
run kd-trace --origin "$(printf '\033[2J1,2')" --dir 1,0
rm -rf "$W"
