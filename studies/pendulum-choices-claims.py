"""The pendulum's claims of Hamann et al. (ALife 2010) judged under each setting of the two
choices the paper leaves open (studies/pendulum-choices.toml; docs/scenarios.md, "Choices the
paper leaves open"): the task's defaults (the first study's runs), an actuator gain of 10, and
soft walls. ahhs-report study judges a study of that plan with these rows: the paper's two
pendulum claims per setting (studies/paper-2010-claims.py), each setting's evolution speed
against its own maximum, and a last row that says whether the verdict depends on the choice."""
import importlib.util
import os

from claims_lib import Claims

_spec = importlib.util.spec_from_file_location(
    "paper_2010_claims", os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                      "paper-2010-claims.py"))
paper = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(paper)

# (configuration suffix in the plan, the setting's words in a claim)
SETTINGS = [("", "task defaults"), ("-gain10", "actuator gain 10"), ("-soft", "soft walls")]
SAME = "Pendulum: the verdict on AHHS2-15 against AHHS1-60 is the same in every setting"


def verdict_word(verdict):
    """"reproduced (n = 20, 20)" -> "reproduced"."""
    return verdict.split(" (n = ")[0]


def make_claims(configs, maxima, stat="best"):
    c = Claims(configs, maxima, stat)
    better = []
    for suffix, setting in SETTINGS:
        paper.pendulum(c, suffix, setting)  # two rows: "is better than", then the speed
        better.append((setting, c.rows[-2][3]))
    paper_text = "(one setting: the paper's)"
    if any(v == "open" for _, v in better):
        c.add(SAME, paper_text, "not every setting has a verdict yet", "open")
        return c.rows
    words = [verdict_word(v) for _, v in better]
    ours = "; ".join(f"{s}: {w}" for (s, _), w in zip(better, words))
    same = len(set(words)) == 1
    c.add(SAME, paper_text, ours, "holds in every setting" if same else "depends on the choice")
    return c.rows
