"""Seeded fuzz of the module's scene dicts (tests/fuzz/README.md): random mutations of a valid
scene's dict — a key deleted or added, a value replaced by None, NaN, ±inf, an integer beyond 64
bits, a string, bytes, an object, a dict or list that contains itself, dicts nested thousands deep
— through weavelab.Scene(dict), scene[key] = value and scene.update, each case in a child
interpreter so that a crash is a failed case. Every case must end with the scene accepted or a
weavelab.SceneError naming a key, and the interpreter alive; an accepted small scene must build
its Model or refuse it with a ValueError. WEAVELAB_FUZZ_CASES=N multiplies the case count."""
import os
import subprocess
import sys
import unittest

import weavelab
from support import HANGING_WIND

HERE = os.path.dirname(os.path.abspath(__file__))

CHILD = r'''
import math, random, sys
import weavelab, support

VALUES = [None, math.nan, math.inf, -math.inf, 10**30, -2**63 - 1, 2**64, 10**1000, 0, -1, 1e300, 1e-300,
          "text", "", b"bytes", True, 1j, object(), [], {}, [None], [math.nan] * 3, {"a": None}, (1, 2), {1, 2}]


def odd(rng):
    kind = rng.randrange(5)
    if kind == 0:
        d = {"warps": 5}
        d["self"] = d
        return d
    if kind == 1:
        l = [1.0]
        l.append(l)
        return l
    if kind == 2:
        d = {}
        for _ in range(rng.choice([40, 3000])):
            d = {"a": d}
        return d
    if kind == 3:
        l = 0.0
        for _ in range(rng.choice([40, 3000])):
            l = [l]
        return l
    return rng.choice(VALUES)


def leaves(d, path=()):
    for k, v in d.items():
        if isinstance(v, dict):
            yield from leaves(v, path + (k,))
        else:
            yield path + (k,), v


def mutate(d, rng):
    paths = list(leaves(d))
    for _ in range(rng.choice([1, 1, 2, 3])):
        path, _ = rng.choice(paths)
        table = d
        for k in path[:-1]:
            table = table[k]
        kind = rng.randrange(4)
        if kind == 0:
            table.pop(path[-1], None)
        elif kind == 1:
            table["unknown_key"] = odd(rng)
        else:
            table[path[-1]] = odd(rng) if rng.random() < 0.5 else rng.choice(VALUES)


def small():
    return support.small_scene(weavelab, size=5, duration=0.01)


def case(seed):
    rng = random.Random(seed)
    base = small()
    how = rng.randrange(3)
    try:
        if how == 0:
            d = base.to_dict()
            mutate(d, rng)
            scene = weavelab.Scene(d)
        elif how == 1:
            key = rng.choice(sorted(".".join(p) for p, _ in leaves(base.to_dict())))
            base[key] = odd(rng) if rng.random() < 0.5 else rng.choice(VALUES)
            scene = base
        else:
            keys = sorted(".".join(p) for p, _ in leaves(base.to_dict()))
            base.update({rng.choice(keys): rng.choice(VALUES) for _ in range(2)})
            scene = base
    except weavelab.SceneError as e:
        assert e.key, "SceneError without a key: %s" % e
        return "refused"
    try:
        weavelab.Model(scene, "yarn").describe()
    except ValueError:
        return "model refused"
    return "accepted"


first, count = int(sys.argv[1]), int(sys.argv[2])
tally = {}
for seed in range(first, first + count):
    outcome = case(seed)
    tally[outcome] = tally.get(outcome, 0) + 1
print(tally)
'''


class SceneDictFuzz(unittest.TestCase):
    def test_every_mutated_dict_is_accepted_or_refused_naming_a_key(self):
        cases = 100 * max(1, int(os.environ.get("WEAVELAB_FUZZ_CASES", "1")))
        batch = 50  # per child interpreter: a crash loses at most one batch, and names it
        tally = {}
        for first in range(0, cases, batch):
            done = subprocess.run([sys.executable, "-c", CHILD, str(first), str(min(batch, cases - first))],
                                  capture_output=True, text=True, cwd=HERE, timeout=600)
            self.assertEqual(done.returncode, 0, "cases %d.. : %s" % (first, done.stderr[-3000:]))
            for outcome, n in eval(done.stdout.strip().splitlines()[-1]).items():
                tally[outcome] = tally.get(outcome, 0) + n
        print("scene dict fuzz: %d cases: %s" % (cases, tally))
        self.assertEqual(sum(tally.values()), cases)
        self.assertGreater(tally.get("refused", 0), cases // 3)
        self.assertGreater(tally.get("accepted", 0), 0)


class SelfContactDistance(unittest.TestCase):
    def test_a_distance_no_model_can_take_is_refused_at_the_edit(self):
        scene = weavelab.load_scene(HANGING_WIND)
        scene["self_contact.enabled"] = True
        with self.assertRaises(weavelab.SceneError) as e:
            scene["self_contact.activation_distance_m"] = 0.01  # ten times the 1 mm node spacing
        self.assertEqual(e.exception.key, "self_contact.activation_distance_m")
        self.assertIn("√½ × the node spacing", str(e.exception))
        self.assertNotIn("activation_distance_m", scene.to_dict()["self_contact"])  # left as it was
        scene["self_contact.activation_distance_m"] = 0.0005
        self.assertEqual(scene["self_contact.activation_distance_m"], 0.0005)


if __name__ == "__main__":
    unittest.main()
