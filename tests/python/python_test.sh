#!/usr/bin/env bash
# The Python package (python/ahhs) against the built tools: python_test.sh BIN_DIR MODULE. The
# evaluation client's test runs real processes on the bus, inside a private network namespace.
bin=${1:?usage: python_test.sh BIN_DIR MODULE}
module=${2:?usage: python_test.sh BIN_DIR MODULE}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
[[ $module == test_evaluate || $module == test_search ]] && ahhs_netns "$0" "$@"
export AHHS_BIN=$bin PYTHONPATH=$AHHS_SOURCE_DIR/python
cd "$AHHS_SOURCE_DIR/python/tests" && exec /usr/bin/python3 -m unittest -v "$module"
