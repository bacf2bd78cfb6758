#!/bin/bash
# Usage: repro.sh HW3_BINARY — re-runs the adversarial cases of the checker and the CLI: forged
# grades, answers that take the grader down, files damaged or left behind, the output contract,
# and refusals of what can be answered. Prints each command, its exit status, time, peak memory,
# stderr and what it wrote. Devices are replicas made here (run as root for mknod), never /dev's.
B=$(realpath "${1:?binary}")
W=$(mktemp -d /tmp/hw3_repro.XXXX); cd "$W" || exit 1
show(){ printf '%s' "$1" | head -c "${2:-200}" | tr '\n' '|' | cat -v; }
# run [T=secs] [M=kB] hw3 args…: exit, stderr, time, peak memory, what was written to stdout
run(){ echo "\$ hw3 $(show "$*" 150)"
  /usr/bin/time -f '%e %M' -o time.txt timeout ${T:-20} bash -c "ulimit -v ${M:-4000000}; exec \"\$0\" \"\$@\"" "$B" "$@" > out.txt 2> err.txt
  local rc=$?; read -r s kb < <(tail -1 time.txt)
  echo "  exit $rc; ${s}s, ${kb} kB; stdout $(wc -c <out.txt) B; stderr $(wc -l <err.txt) lines, longest $(awk '{ if (length>m) m=length } END { print m+0 }' err.txt) chars: $(show "$(cat err.txt)" 260)"; }
key(){ { echo "[meta]"; echo "seed = 0"; for q in q1 q2 q3 q4 q5; do "$B" variant --question $q --seed 0 | sed -n '/^Solution, as an answers file:/,$p' | sed '1d;/^\[meta\]$/d;/^seed = /d'; done; } > key.toml; }
key
# grade PART FILE: the line of the report for one part
grade(){ "$B" check "$2" > g.txt 2>&1; grep -F " $1 " g.txt | head -1 | sed 's/  */ /g'; grep '^hw3:' g.txt | cut -c1-200; }
swap(){ python3 - "$@" <<'PY'
import re, sys
src, key, value, out = sys.argv[1:5]
text = open(src).read()
section, name = key.split('.', 1)
lines = text.split('\n'); cur = None
for i, l in enumerate(lines):
    m = re.match(r'^\[(\w+)\]$', l)
    if m: cur = m.group(1); continue
    if cur == section and re.match(r'^' + re.escape(name) + r' = ', l):
        lines[i] = f'{name} = {value}'
open(out, 'w').write('\n'.join(lines))
PY
}

echo "## A. forged grades: a non-finite formula, a finite bound where the key says inf"
for f in '"1/0"' '"-1/0"' '"10^400"' '"B/(A-A)"' '"(p - o)/0"'; do
  swap key.toml q2a.t_formula "$f" f.toml; echo "  q2a.t_formula = $f -> $(grade q2a.t_formula f.toml)"; done
swap key.toml q2b.normal_formula '"(p - o)/0"' f.toml; echo "  q2b.normal_formula = \"(p - o)/0\" -> $(grade q2b.normal_formula f.toml)"
for v in 0 2.5 -7 1e308; do
  sed "s/{ path = \[\"x<3\", \"y>=1\"\], tmin = 2.0, tmax = \"inf\" }/{ path = [\"x<3\", \"y>=1\"], tmin = 2.0, tmax = $v }/" key.toml > f.toml
  echo "  q3d leaves tmax = $v -> $(grade q3d.leaves f.toml)"; done
sed 's/{ path = \["x<3", "y<1"\], tmin = 0.0, tmax = "inf" },/{ path = ["x<3", "y<1"], tmin = 0.0, tmax = 0.0 },/' key.toml | awk '/^\[q3e\]/{q=1} q && /^leaves/{l=1} {print}' > f.toml
echo "  q3e [x<3, y<1] t in [0, 0] -> $(grade q3e.leaves f.toml)"

echo "## B. one file takes the grader down"
p16=$(python3 -c 'print("LGE|L(D|G)*D" + "(D|G)"*16 + "E")'); echo "  answer of ${#p16} chars"
swap key.toml q5a.a_missed "\"$p16\"" f.toml; T=90 run check f.toml
python3 -c 'print("[meta]\nseed = 0\n[q5a]\na_missed = \"" + "("*30000 + "L" + ")"*30000 + "E\"")' > f.toml; run check f.toml
python3 -c 'print("[meta]\nseed = 0\n[q5a]\na_missed = \"L" + "D"*30000 + "E\"")' > f.toml; T=90 run check f.toml
python3 -c 'print("[meta]\nseed = 0\n[q5a]\na_missed = \"L" + "(D|S|G)*"*2000 + "E\"")' > f.toml; T=90 run check f.toml
rm -f fifo.toml; mkfifo fifo.toml; T=5 run check fifo.toml
mkdir -p class; cp key.toml class/a.toml; rm -f class/b.toml; mkfifo class/b.toml; T=5 run check class
rm -f fifo.hdr; mkfifo fifo.hdr; T=5 run irradiance --env fifo.hdr --normal 0,0,1 --method sh9

echo "## C. files damaged or left behind"
cp key.toml s.toml; run check s.toml --out s.toml; echo "  s.toml afterwards: $(head -c 60 s.toml | tr '\n' '|')"
# Replicas of /dev/null, /dev/full and /dev/stdout: the machine's own nodes are never put at risk.
mknod null c 1 3; mknod full c 1 7; ln -s /proc/self/fd/1 stdout
for d in stdout null full; do run check key.toml --out $d; echo "  $d afterwards: $(stat -L -c %F $d 2>&1)"; done
mkdir -p empty; rm -rf gs; run check empty --format gradescope --out gs; echo "  gs exists afterwards: $([ -e gs ] && echo yes || echo no)"
mkdir -p twins/a twins/b; cp key.toml twins/a/x.toml; cp key.toml twins/b/x.toml; rm -rf gs; run check twins/a/x.toml twins/b/x.toml --format gradescope --out gs; echo "  gs exists afterwards: $([ -e gs ] && echo yes || echo no)"
for n in 247 251 255 256; do name=$(python3 -c "print('a'*($n-4) + '.png')"); T=60 run render still --spp 1 --size 16x16 --out "$name"; done
for sig in INT TERM HUP; do rm -f .hw3* slow.png; timeout --preserve-status -s $sig 0.5 "$B" render still --spp 4096 --size 256x256 --allow-large --out slow.png >/dev/null 2>&1; echo "  render interrupted by SIG$sig: exit $?, temporaries left: $(ls -a | grep -c '^\.hw3')"; done

echo "## D. the contract"
for c in "scenes" "answers" "template" "check key.toml" "sphere --origin -5,1,0 --dir 1,0,0 --center 0,0,0 --radius 2" "kd-trace --origin 5,0 --dir -1,1" "paths cornell" "effect-tables" "variant --question q2 --seed 3" "irradiance --env sky --normal 0,0,1 --method sh9"; do
  $B $c >&- 2> err.txt; echo "  hw3 $c >&-: exit $?; $(show "$(cat err.txt)" 160)"; done
run template --seed $(python3 -c 'print("9"*400)')
run check "$(python3 -c 'print("d/"*200 + "x.toml")')"
printf '[meta]\nseed = 0\n[q2a]\nt = "%s\n' "$(python3 -c 'print("x"*500)')" > long.toml; run check long.toml
run render still --spp 1 --size 16x16 --out "$(printf 'e\033[31mred\u202Eevil.png')"
run sphere --origin -1e39,0,0 --dir 1,0,0 --center 0,0,0 --radius 1 --precision f32
run irradiance --env constant:5e307 --normal 0,0,1 --method sh9
python3 - <<'PY'
import struct
w, h = 16, 8
rows = bytearray()
for y in range(h):
    for x in range(w): rows += bytes([3, 3, 3, 1])   # mantissa 3, exponent byte 1: about 7e-41, a subnormal f32
open('sub.hdr','wb').write(b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n' % (h, w) + bytes(rows))
PY
for m in sh9 map; do run irradiance --env sub.hdr --normal 0,0,1 --method $m; done

echo "## E. refusing what can be answered"
for o in -1e5 -1e6 -1e7; do run sphere --precision f32 --method stable --origin $o,0.5,0 --dir 1,0,0 --center 0,0,0 --radius 1; done
