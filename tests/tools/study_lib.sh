# Shared by the ahhs-study tests (study_test.sh, study_slurm_test.sh): the tiny plan they run and
# the bit-for-bit comparison of two studies' runs. Needs $src, $tmp, fail and dump_run
# (tests/lib.sh).


runs="pend2/seed-1 pend2/seed-2 pend1/seed-1 pend1/seed-2"
# same_study DIR_A DIR_B WHAT: every run of $runs identical, best.json too (but its run id).
same_study() {
  for r in $runs; do
    dump_run "$1/$r" >$tmp/a.dump; dump_run "$2/$r" >$tmp/b.dump
    [[ -s $tmp/a.dump ]] || fail "$3: $r is empty"
    cmp -s $tmp/a.dump $tmp/b.dump || fail "$3: $r differs"
    # best.json: the same genome and metadata but the run id (host, process, time).
    grep -v '"run":' "$1/$r/best.json" >$tmp/a.json; grep -v '"run":' "$2/$r/best.json" >$tmp/b.json
    cmp -s $tmp/a.json $tmp/b.json || { diff $tmp/a.json $tmp/b.json; fail "$3: $r/best.json differs"; }
  done
  echo "$3: every run identical"
}

# tiny_plan FILE GENERATIONS: two small pendulum configurations, two seeds each.
tiny_plan() {
  cat >$1 <<PLAN
name = "tiny"
[defaults]
generations = $2
population = 24
duration = 20.0
[[config]]
name = "pend2"
preset = "$src/configs/pendulum-ahhs2-15.toml"
seeds = 2
set = { hormones = 4, rules = 6 }
[[config]]
name = "pend1"
preset = "$src/configs/pendulum-ahhs1-60.toml"
seeds = 2
[config.set]
rules = 20
PLAN
}
