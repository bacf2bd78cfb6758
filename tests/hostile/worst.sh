#!/bin/bash
# Usage: worst.sh HW3_BINARY — the worst input each subcommand accepts without --allow-large, run under
# /usr/bin/time -v: wall time, peak memory (maximum resident set size) and exit status. Prints `uptime`
# first: on a shared machine the wall times scale with the load.
B=$(realpath "${1:?binary}")
W=$(mktemp -d /tmp/hostile_worst.XXXX); cd "$W"
uptime
# A 2048 × 1024 lat-long map (the default texel limit), flat RGBE (8 MiB).
python3 - <<'PY'
import os
w, h = 2048, 1024
with open('big.hdr', 'wb') as f:
    f.write(b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n' % (h, w))
    f.write(bytes([128, 128, 128, 129]) * (w * h))
PY
# An answers file at the 256 KiB limit, all unknown keys.
python3 -c "
import sys
out = '[meta]\nseed = 0\n'
i = 0
while len(out) < 256 * 1024 - 32:
    out += f'k{i} = {i}\n'; i += 1
open('keys.toml', 'w').write(out)"
$B template --seed 9223372036854775807 > max_seed.toml
printf '| command | exit | wall s | peak MB |\n|---|---|---|---|\n'
measure() {
    /usr/bin/time -v "$B" "$@" > out.txt 2> err.txt
    local rc=$?
    local wall=$(grep 'Elapsed (wall' err.txt | awk '{print $NF}')
    local kb=$(grep 'Maximum resident' err.txt | awk '{print $NF}')
    echo "| \`hw3 $*\` | $rc | $wall | $((kb / 1024)) |"
}
measure answers
measure sphere --origin -1e15,1,0 --dir 1,0,0 --center 0,0,0 --radius 1e15 --json
measure template --seed 9223372036854775807
measure check max_seed.toml
measure check keys.toml
measure effects-table
measure variant --question q5 --seed 9223372036854775807
measure solution --seed 9223372036854775807
measure irradiance --env big.hdr --normal 0,0,1 --method sh9
measure irradiance --env big.hdr --normal 0,0,1 --method map --samples 1048576
measure irradiance --env sky --normal 0,0,1 --method sh9 --size 1024
measure irradiance --env sky --normal 0,0,1 --method uniform --samples 1048576
measure kd-trace --origin 5,0 --dir -1,1 --json
measure scenes
measure effects fog
measure render fog --size 2048x2048 --spp 1 --out fog.png
measure render cornell --size 2048x2048 --spp 1 --out cornell.png
measure figures --out "$W/figures"
# The worst light-path answers: each of the 18 path parts holds its key's class or'd with a choice
# repeated after a star, as long as the 256-character limit allows, so that every comparison runs
# to the automaton state limit.
python3 - "$B" <<'PY'
import re, subprocess, sys
B = sys.argv[1]
key = subprocess.run([B, 'variant', '--question', 'q5', '--seed', '0'], capture_output=True, text=True).stdout
key = key.split('Solution, as an answers file:')[1]
lines, section = ['[meta]', 'seed = 0'], None
for l in key.splitlines():
    m = re.match(r'^\[(q5\w*)\]$', l)
    if m:
        section = m.group(1); lines.append(l); continue
    m = re.match(r'^(\w+) = "([^"]*)"$', l)
    if section and m and (m.group(1).endswith('_missed') or section == 'q5paths'):
        prefix = '' if m.group(2) == 'none' else m.group(2) + '|'
        k = (256 - len(prefix) - len('L[DGSV]*DE')) // len('[DGSV]')
        lines.append(f'{m.group(1)} = "{prefix}L[DGSV]*D{"[DGSV]" * k}E"')
open('paths.toml', 'w').write('\n'.join(lines) + '\n')
PY
echo "\$ hw3 check paths.toml   (18 light-path answers at the limits)"
/usr/bin/time -f '  %e s wall, %M kB peak, exit %x' "$B" check paths.toml > /dev/null
uptime
rm -rf "$W"
