#!/bin/sh
# man_page.sh PROGRAM OUT.1.gz [NAME]: a manual page from PROGRAM's --help and --version
# (help2man), compressed as Debian wants. Its one-line description is NAME, else the first line
# of the --help ("ahhs-x: what it does").
set -eu
program=$1
out=$2
name=${3:-$("$program" --help 2>&1 | head -1 | sed -e 's/^[^:]*: *//' -e 's/\.$//')}
help2man --no-info --no-discard-stderr --section=1 --source=AHHS --name="$name" "$program" |
  gzip -9n >"$out.tmp"
mv "$out.tmp" "$out"
