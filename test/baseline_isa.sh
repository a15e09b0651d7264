#!/usr/bin/env bash
# A portable build (MPM_SDEM_NATIVE=OFF, issue 42) must run on any x86-64: outside the code that
# Highway compiles per target and chooses at run time (the namespaces N_SSSE3, N_SSE4, N_AVX2,
# N_AVX3, N_AVX3_DL), no function of ours may use an instruction beyond the baseline's SSE2 -
# no AVX or AVX-512 (VEX- and EVEX-encoded mnemonics start with "v"), FMA, SSE4 or BMI. Checks
# every shared library and program of the build's devel space by disassembly and names each
# function that breaks the rule. tzcnt is allowed: it is encoded as rep bsf, which a CPU without
# BMI runs as bsf, with the same result for the non-zero words GCC uses it on.
# Usage: test/baseline_isa.sh DEVEL_LIB_DIR
set -euo pipefail
lib="$1"
files=()
while IFS= read -r -d '' f; do
  file -b "$f" | grep -q '^ELF' && files+=("$f")
done < <(find "$lib" -maxdepth 2 -type f \( -name 'libmpm_sdem*.so' -o -perm -u+x \) -print0)
[ ${#files[@]} -gt 0 ] || { echo "no binaries under $lib" >&2; exit 1; }
status=0
for f in "${files[@]}"; do
  # One line per offending function: its name and its first offending instruction.
  found="$(objdump -d -C --no-show-raw-insn "$f" | awk '
    /^[0-9a-f]+ <.*>:$/ { name = $0; sub(/^[0-9a-f]+ </, "", name); sub(/>:$/, "", name);
                          allowed = name ~ /::N_(SSSE3|SSE4|AVX2|AVX3|AVX3_DL)::/; reported = 0; next }
    allowed || reported { next }
    {
      split($0, part, "\t"); insn = part[2]; split(insn, word, " "); m = word[1];
      if (m ~ /^v/ && m !~ /^ver[rw]$/ || m ~ /^(roundsd|roundss|roundpd|roundps|blendvpd|blendvps|pblendvb|ptest|pmulld|pminsd|pmaxsd|dppd|dpps|insertps|extractps|pextrd|pextrq|pinsrd|pinsrq|popcnt|lzcnt|andn|bextr|shlx|shrx|sarx|bzhi|pdep|pext|mulx|rorx)$/) {
        print name "\t" insn; reported = 1
      }
    }')"
  if [ -n "$found" ]; then
    echo "$f: functions outside the per-target code use instructions beyond SSE2:"
    echo "$found" | head -20
    status=1
  fi
done
[ $status -eq 0 ] && echo "${#files[@]} binaries: only the per-target code goes beyond SSE2"
exit $status
