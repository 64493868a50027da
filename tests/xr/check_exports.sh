#!/bin/sh
# The runtime library exports exactly one symbol: xrNegotiateLoaderRuntimeInterface.
# usage: check_exports.sh LIBRARY
set -u
symbols=$(nm -D --defined-only "$1" | awk '{print $3}')
echo "$symbols"
[ "$symbols" = "xrNegotiateLoaderRuntimeInterface" ] || { echo "FAIL: exports more (or other) than the negotiation function"; exit 1; }
echo "PASS"
