#!/usr/bin/env bash
# The preset scripts/test.sh builds and tests (and scripts/downstream.sh installs): release under CI, where it has
# warnings as errors, else ci.
if [ -n "${CI:-}" ]; then echo release; else echo ci; fi
