#!/usr/bin/env python3
"""Which association errors each filter's MRCLAM error comes from: oracles.

MRCLAM's 15 cylinders stand in clusters of two or three, 0.15-0.2 m apart,
the clusters about 2 m apart. Without the barcodes an association has two
decisions to make: which cluster a sighting is of, and which cylinder of it.
This runs each filter with IDs (configs/mrclam/<filter>.ini, its 0.9999 ID
gate on) on each robot of dataset 6 with three associations given through
--associations-from, and without IDs (configs/mrclam/<filter>_jcbb.ini),
and prints the landmark RMSE against the Vicon ground truth:
  - barcodes: the dataset's own IDs (the with-ID figure of issue 40);
  - cluster oracle: every sighting given its barcode's cluster (one landmark
    per cluster): what an association that always finds the right cluster
    and cannot tell the cylinders of one apart achieves;
  - nearest in cluster: the barcode's cluster, and in it the cylinder whose
    landmark, in the with-barcode EKF's final map, is nearest (Mahalanobis,
    the noise of one sighting) to the sighting predicted from that EKF's pose
    at the sighting's step: what separating the cylinders by position
    achieves, with the best map a filter of this data has (also printed: how
    often that nearest cylinder is the barcode's);
  - none: the filter's own association without IDs, and how often it hits
    the barcode's cluster and cylinder;
  - barcodes / cluster oracle, the no-ID run's left-outs left out: the first
    two again, on only the sightings the filter without IDs used (its ambiguity
    waits, gates and poorly observed sightings left out): what its caution
    alone costs, apart from its choice of landmarks.
Each measurement's barcode comes from `esif export g2o --landmark-edge br`
(one BR edge per measurement, in step order); clusters are the groups of
cylinders closer than 1 m in the ground truth the importer writes beside the
rawlog.

Usage: bench/mrclam_association_oracles.py ESIF OUT_DIR
(rawlogs out/data/mrclam6_r1..5.rawlog, made by `esif import mrclam`).
"""
import configparser
import json
import math
import os
import statistics
import subprocess
import sys

# The dataset's row reader, angle wrap and cylinder clusters (closer than 1 m)
# are the true-pose bench's, so both benches group the cylinders alike.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrclam_true_pose_association import clusters_of as clusters, rows as data_rows, wrap  # noqa: E402

FILTERS = ["ekf", "slsjf", "dslam_lmj", "dslam"]  # configs/mrclam/<filter>.ini and <filter>_jcbb.ini


def measurements(esif, rawlog, g2o):
    """(step, index in step, barcode cylinder, bearing, range) per measurement, and the step count."""
    subprocess.run([esif, "export", "g2o", "--landmark-edge", "br", "-r", rawlog, "-o", g2o],
                   check=True, stdout=subprocess.DEVNULL)
    lines = open(g2o).read().splitlines()
    steps = sum(1 for line in lines if line.startswith("VERTEX_SE2 "))
    out, last, k = [], -1, 0
    for line in lines:
        if line.startswith("BR "):
            f = line.split()
            step = int(f[1])
            k = k + 1 if step == last else 0
            last = step
            out.append((step, k, int(f[2]) - steps, float(f[3]), float(f[4])))
    return out, steps


LEFT_OUT = None  # a row's landmark when the sighting is to be left out
FIRST_LEFT_OUT_ID = 100000  # above every cylinder's and cluster's ID


def write_associations(folder, steps, rows):
    """An associations.txt for --associations-from. A with-ID filter takes no
    rejected row (every measurement needs its ID), so a sighting to be left
    out gets a landmark of its own that no other sighting has: a landmark
    seen once is all unknown but that sighting, and moves nothing else."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "associations.txt"), "w") as f:
        f.write("# esif associations.txt: an oracle of bench/mrclam_association_oracles.py\n")
        f.write("# columns: step measurement kind landmark_id\n# steps %d\n" % steps)
        seen, left_out = set(), 0
        for step, k, landmark in rows:
            if landmark is LEFT_OUT:
                landmark, left_out = FIRST_LEFT_OUT_ID + left_out, left_out + 1
            f.write("%d %d %s %d\n" % (step, k, "matched" if landmark in seen else "new", landmark))
            seen.add(landmark)


def used_by(run, meas):
    """Per measurement: whether the run without IDs used it (not rejected)."""
    return [kind != "rejected" for (_, _, kind, _) in data_rows(os.path.join(run, "associations.txt"))][:len(meas)]


def association_shares(run, meas, cluster):
    """Of the measurements a run without IDs used: the share on a landmark of the
    barcode's cluster and on the barcode's cylinder (through each landmark's
    identity), and the share of all it left out."""
    identity = {int(r[0]): int(r[1]) for r in data_rows(os.path.join(run, "landmark_identities.txt"))}
    rows = list(data_rows(os.path.join(run, "associations.txt")))
    used = same_cluster = same_cylinder = 0
    for (_, _, barcode, _, _), (_, _, kind, landmark) in zip(meas, rows):
        if kind == "rejected":
            continue
        used += 1
        true = identity.get(int(landmark), -1)
        same_cluster += true in cluster and cluster[true] == cluster[barcode]
        same_cylinder += true == barcode
    return same_cluster / used, same_cylinder / used, 1 - used / len(meas)


def nearest_in_cluster(run, meas, cluster, sr, sb):
    """The oracle's landmark for each measurement, and the share that is the barcode's cylinder."""
    poses = [tuple(map(float, r)) for r in data_rows(os.path.join(run, "trajectory.tum"))]
    landmarks = {int(r[0]): (float(r[1]), float(r[2])) for r in data_rows(os.path.join(run, "landmarks.txt"))}
    rows, right = [], 0
    for step, k, barcode, bearing, rng in meas:
        _, x, y, _, _, _, qz, qw = poses[step]
        th = 2 * math.atan2(qz, qw)

        def d2(j):
            lx, ly = landmarks[j]
            er = (rng - math.hypot(lx - x, ly - y)) / sr
            eb = wrap(bearing - wrap(math.atan2(ly - y, lx - x) - th)) / sb
            return er * er + eb * eb
        best = min((j for j in landmarks if cluster[j] == cluster[barcode]), key=d2)
        right += best == barcode
        rows.append((step, k, best))
    return rows, right / len(meas)


def run_filter(esif, rawlog, out, config, associations_from=None):
    cmd = [esif, "run", "-q", "--no-figures", "--config", config, "--rawlog", rawlog, "--out", out]
    if associations_from:
        cmd += ["--associations-from", associations_from]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    path = os.path.join(out, "stats.json")
    if not os.path.exists(path):
        return None
    return without_left_out_landmarks(out, json.load(open(path)))


def without_left_out_landmarks(out, stats):
    """The run's stats with its landmark count ("mapped") and RMSE over the
    landmarks that do not stand for one left-out sighting each (the run counts
    and scores those with the rest)."""
    ids = [r[0] for r in data_rows(os.path.join(out, "landmarks.txt"))]
    identity = {r[0]: r[1] for r in data_rows(os.path.join(out, "landmark_identities.txt"))}
    # landmark_errors.csv: the landmarks of landmarks.txt that have a true
    # landmark, in that order.
    errors = [r.split(",") for r in open(os.path.join(out, "landmark_errors.csv")).read().split()[1:]]
    scored = [i for i in ids if identity.get(i, "-1") != "-1"]
    if len(scored) != len(errors) or any(identity[i] != e[0] for i, e in zip(scored, errors)):
        sys.exit("bench/mrclam_association_oracles.py: %s: landmark_errors.csv does not follow landmarks.txt" % out)
    kept = [e for i, e in zip(scored, errors) if int(i) < FIRST_LEFT_OUT_ID]
    stats["mapped"] = sum(int(i) < FIRST_LEFT_OUT_ID for i in ids)
    if kept:
        stats["landmark_rmse_m"] = math.sqrt(sum(float(e[1]) ** 2 + float(e[2]) ** 2 for e in kept) / len(kept))
    return stats


ASSOCIATIONS = ["barcodes", "cluster oracle", "nearest in cluster", "none: JCBB without IDs",
                "barcodes, the no-ID run's left-outs left out", "cluster oracle, the no-ID run's left-outs left out"]


def median_rmse(runs):
    done = [s["landmark_rmse_m"] for s in runs if s]
    return statistics.median(done) if done else None


def print_reading(runs):
    """Each filter's medians against issue 40's target: where its no-ID run's
    sightings, and where its partition of them into landmarks, would put it."""
    columns = [ASSOCIATIONS[4], ASSOCIATIONS[5], ASSOCIATIONS[3]]
    print("Issue 40's target against the medians above: the barcodes and the cluster oracle on the sightings the no-ID "
          "run used, and the no-ID run itself; in brackets the ratio to the barcodes' median on all sightings (the "
          "target: at most 1.5x).")
    print()
    print("| filter | target [m] | barcodes, used sightings [m] | cluster oracle, used sightings [m] | without IDs [m] |")
    print("|---|---:|---|---|---|")
    for f in FILTERS:
        barcodes = median_rmse(runs[(f, "barcodes")])
        if barcodes is None:
            continue
        target = 1.5 * barcodes
        cells = []
        for a in columns:
            m = median_rmse(runs[(f, a)])
            cells.append("-" if m is None else "%.3f (%.2fx%s)" % (m, m / barcodes, "" if m <= target else ", above"))
        print("| %s | %.3f | %s |" % (f, target, " | ".join(cells)))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-2])
    esif, out = sys.argv[1:3]
    cal = configparser.ConfigParser()
    cal.read("configs/calibration/mrclam.ini")
    sr = float(cal["calibration"]["sighting_range_std_m"])
    sb = math.radians(float(cal["calibration"]["sighting_bearing_std_deg"]))
    runs = {(f, a): [] for f in FILTERS for a in ASSOCIATIONS}
    shares = {f: [] for f in FILTERS}
    right_shares = []
    for robot in range(1, 6):
        rawlog = "out/data/mrclam6_r%d.rawlog" % robot
        truth = "out/data/mrclam6_r%d_ground_truth.txt" % robot
        if not os.path.exists(rawlog):
            sys.exit("bench/mrclam_association_oracles.py: %s not present (esif import mrclam)" % os.path.abspath(rawlog))
        base = os.path.join(out, "r%d" % robot)
        os.makedirs(base, exist_ok=True)
        cylinders = {int(r[6]): (float(r[0]), float(r[1])) for r in data_rows(truth)}
        cluster = clusters(cylinders)
        meas, steps = measurements(esif, rawlog, os.path.join(base, "br.g2o"))
        oracles = {"cluster oracle": os.path.join(base, "cluster_ids"), "nearest in cluster": os.path.join(base, "nearest_ids")}
        write_associations(oracles["cluster oracle"], steps, [(s, k, cluster[b]) for s, k, b, _, _ in meas])
        ekf_barcodes = os.path.join(base, "ekf_barcodes")
        for f in FILTERS:
            with_ids = "configs/mrclam/%s.ini" % f
            runs[(f, "barcodes")].append(run_filter(esif, rawlog, os.path.join(base, f + "_barcodes"), with_ids))
            if f == FILTERS[0]:
                rows, share = nearest_in_cluster(ekf_barcodes, meas, cluster, sr, sb)
                right_shares.append(share)
                write_associations(oracles["nearest in cluster"], steps, rows)
            for name, folder in oracles.items():
                runs[(f, name)].append(run_filter(esif, rawlog, os.path.join(base, f + "_" + name.replace(" ", "_")),
                                                  with_ids, folder))
            no_ids = os.path.join(base, f + "_no_ids")
            stats = run_filter(esif, rawlog, no_ids, "configs/mrclam/%s_jcbb.ini" % f)
            runs[(f, ASSOCIATIONS[3])].append(stats)
            shares[f].append(association_shares(no_ids, meas, cluster) if stats else None)
            used = used_by(no_ids, meas) if stats else None
            for name, landmark_of in ((ASSOCIATIONS[4], lambda b: b), (ASSOCIATIONS[5], lambda b: cluster[b])):
                if used is None:  # no run without IDs, no sightings it used
                    runs[(f, name)].append(None)
                    continue
                folder = os.path.join(base, f + "_" + name.split(",")[0].replace(" ", "_") + "_used")
                write_associations(folder, steps, [(s, k, landmark_of(b) if u else LEFT_OUT)
                                                   for (s, k, b, _, _), u in zip(meas, used)])
                runs[(f, name)].append(run_filter(esif, rawlog, folder + "_run", with_ids, folder))

    print("| filter | association | landmark RMSE median [m] (per robot) | landmarks per robot |")
    print("|---|---|---|---|")
    for f in FILTERS:
        for a in ASSOCIATIONS:
            rmse = [s["landmark_rmse_m"] if s else None for s in runs[(f, a)]]
            median = median_rmse(runs[(f, a)])
            print("| %s | %s | %s (%s) | %s |" % (
                f, a, "-" if median is None else "%.3f" % median,
                " ".join("-" if v is None else "%.2f" % v for v in rmse),
                " ".join("-" if s is None else "%d" % s["mapped"] for s in runs[(f, a)])))
    print()
    print_reading(runs)
    print()
    print("Nearest in cluster: the oracle's cylinder is the barcode's for %s of the measurements (robots 1-5)."
          % " ".join("%.0f%%" % (100 * v) for v in right_shares))
    print()
    print("Without IDs (`configs/mrclam/<filter>_jcbb.ini`), per robot: of the measurements the filter used, the share on a "
          "landmark of the barcode's cluster and on the barcode's cylinder (through each landmark's identity); and the "
          "share it left out (waits, gates, unconfirmed, poorly observed).")
    print()
    print("| filter | right cluster | right cylinder | left out |")
    print("|---|---|---|---|")
    for f in FILTERS:
        cols = [" ".join("-" if v is None else "%.1f%%" % (100 * v[c]) for v in shares[f]) for c in range(3)]
        print("| %s | %s |" % (f, " | ".join(cols)))


if __name__ == "__main__":
    main()
