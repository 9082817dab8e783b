#!/usr/bin/env python3
"""How ambiguous MRCLAM's cylinders are to a sensor that knows where it is.

For every landmark measurement of MRCLAM dataset 6 (robots 1-5), the robot's
Vicon pose at that time and every cylinder's Vicon position give the
predicted range and bearing of each cylinder. The nearest cylinder in the
Mahalanobis metric of a noise model is what an association with a perfect
pose would pick. Printed per robot: how often it is the barcode's cylinder,
how often it is in the barcode's cluster (cylinders stand in groups of two or
three 0.15-0.2 m apart, the groups about 2 m apart), and how often a
cylinder of another cluster falls inside the 0.9999 gate. With the noise of
one sighting and with the noise fused for 16 sightings (configs/calibration/
mrclam.ini; measurements as recorded, the calibrated bias of a few cm not
taken out) this separates what the sensor cannot resolve from what the
filters' pose errors add (docs/results/no_ids.md, issue 40).

Usage: bench/mrclam_true_pose_association.py [DATASET_DIR] [CALIBRATION_INI]
(defaults: ../shared/data/mrclam/MRCLAM_Dataset6, configs/calibration/mrclam.ini)
"""
import bisect
import configparser
import math
import os
import sys

GATE_9999 = 18.42  # chi-square(2) quantile 0.9999
CLUSTER_M = 1.0  # cylinders closer than this belong to one cluster


def rows(path):
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                yield line.split()


def clusters_of(landmarks, within_m=CLUSTER_M):
    """Single-linkage groups of cylinders closer than `within_m` (CLUSTER_M: the clusters)."""
    label = {i: i for i in landmarks}
    def root(i):
        while label[i] != i:
            i = label[i]
        return i
    for a in landmarks:
        for b in landmarks:
            if a < b and math.dist(landmarks[a], landmarks[b]) < within_m:
                label[root(b)] = root(a)
    return {i: root(i) for i in landmarks}


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def robot_report(d, robot, landmarks, cluster, barcode_subject, sr, sb):
    truth = [tuple(map(float, r)) for r in rows(os.path.join(d, "Robot%d_Groundtruth.dat" % robot))]
    times = [t[0] for t in truth]
    n = right = same_cluster = other_in_gate = 0
    for t, code, rng, brg in rows(os.path.join(d, "Robot%d_Measurement.dat" % robot)):
        subject = barcode_subject.get(int(code))
        if subject not in landmarks:
            continue  # another robot, or an unknown barcode
        _, x, y, th = truth[min(bisect.bisect_left(times, float(t)), len(truth) - 1)]
        d2 = {}
        for i, (lx, ly) in landmarks.items():
            er = (float(rng) - math.hypot(lx - x, ly - y)) / sr
            eb = wrap(float(brg) - wrap(math.atan2(ly - y, lx - x) - th)) / sb
            d2[i] = er * er + eb * eb
        best = min(d2, key=d2.get)
        n += 1
        right += best == subject
        same_cluster += cluster[best] == cluster[subject]
        other_in_gate += any(v < GATE_9999 and cluster[i] != cluster[subject] for i, v in d2.items())
    return n, right / n, same_cluster / n, other_in_gate / n


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/mrclam/MRCLAM_Dataset6"
    ini = sys.argv[2] if len(sys.argv) > 2 else "configs/calibration/mrclam.ini"
    if not os.path.isdir(d):
        sys.exit("bench/mrclam_true_pose_association.py: %s not present (MRCLAM dataset 6)" % os.path.abspath(d))
    cal = configparser.ConfigParser()
    if not cal.read(ini):
        sys.exit("bench/mrclam_true_pose_association.py: cannot read %s" % ini)
    c = cal["calibration"]
    models = [("one sighting (association)", float(c["sighting_range_std_m"]), float(c["sighting_bearing_std_deg"])),
              ("fused (16 sightings)", float(c["range_std_m"]), float(c["bearing_std_deg"]))]
    barcode_subject = {int(b): int(s) for s, b in rows(os.path.join(d, "Barcodes.dat"))}
    landmarks = {int(r[0]): (float(r[1]), float(r[2])) for r in rows(os.path.join(d, "Landmark_Groundtruth.dat"))}
    cluster = clusters_of(landmarks)
    print("| noise model | robot | measurements | nearest is the cylinder | nearest in its cluster | "
          "another cluster inside the 0.9999 gate |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, sr_m, sb_deg in models:
        for robot in range(1, 6):
            n, right, same, other = robot_report(d, robot, landmarks, cluster, barcode_subject, sr_m, math.radians(sb_deg))
            print("| %s (%.2f m, %.2f deg) | %d | %d | %.1f%% | %.1f%% | %.1f%% |"
                  % (name, sr_m, sb_deg, robot, n, 100 * right, 100 * same, 100 * other))


if __name__ == "__main__":
    main()
