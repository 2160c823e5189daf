#!/bin/sh
# SPDX-License-Identifier: MIT
# The core's promise, proven from the built objects: lib/ calls nothing outside itself
# but compiler runtime helpers, and the fixed build does no floating-point arithmetic.
set -u
lib=$1
defined=$(nm -g --defined-only "$lib" | awk 'NF==3{print $3}' | sort -u)
undef=$(nm -u "$lib" | awk '{print $2}' | grep -v '^$' | sort -u)
bad=""
for sym in $undef; do
  echo "$defined" | grep -qx "$sym" && continue
  case "$sym" in
    __aeabi_*|__udivdi3|__divdi3|__umoddi3|__moddi3|__udivmoddi4|__divmoddi4|__muldi3|__ashldi3|__lshrdi3|__ashrdi3|__clzdi2|__clzsi2|__mulsi3|__divsi3|__udivsi3|__modsi3|__umodsi3|__stack_chk_*) ;;
    *) bad="$bad $sym" ;;
  esac
done
if [ -n "$bad" ]; then
  echo "nm-check: FAIL: $lib needs symbols from outside the core:$bad"; exit 1
fi
if command -v objdump >/dev/null 2>&1; then
  fp=$(objdump -d "$lib" | grep -E -c '\s(cvt[a-z0-9]*|[a-z]*(add|sub|mul|div|sqrt|min|max)s[sd]|ucomis[sd]|comis[sd])\s' || true)
  if [ "$fp" != "0" ]; then
    echo "nm-check: FAIL: $lib contains $fp floating-point instructions"; exit 1
  fi
fi
echo "nm-check: ok: $lib uses no malloc, stdio, libm or floating point (undefined: $(echo $undef | wc -w) internal symbols, all resolved inside)"
