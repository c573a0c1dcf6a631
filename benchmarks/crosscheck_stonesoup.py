"""Record what Stone Soup's ``ChernoffUpdater`` computes at ω = 0.2, 0.5, 0.8 (issue 19, the peer check).

Run in a side environment that has Stone Soup (it is not in the lock):

    python -m venv /tmp/ss && /tmp/ss/bin/pip install stonesoup
    /tmp/ss/bin/python benchmarks/crosscheck_stonesoup.py

Writes ``fusion/data/peers/stonesoup_chernoff.json`` (a peer's computed outputs, with its version and date): the inputs (measurement a, A; prediction b, B), and
for each ω the updater's innovation covariance and posterior; and one case (``detection_case``, ω = 0.8) whose
detection carries its own covariance A2, different from the measurement model's noise covariance A (a track
fused from another node carries its own covariance). Chapter 06 compares them with the
curvature of the Chernoff normaliser and with our Chernoff fusion (``fusion.book.chapters.chernoff``);
``tests/test_chernoff.py`` repeats the comparison live when Stone Soup is installed.
"""

from __future__ import annotations

import json
from datetime import date
from pathlib import Path

import numpy as np

A = [[2.0, 0.3], [0.3, 1.0]]      # measurement covariance
B = [[1.0, -0.2], [-0.2, 3.0]]    # prediction covariance
a = [1.0, 2.0]                    # measurement mean
b = [0.5, -1.0]                   # prediction mean
OMEGAS = (0.2, 0.5, 0.8)
A2 = [[5.0, -1.0], [-1.0, 2.5]]   # the detection's own covariance in the detection case


def run() -> dict:
    import stonesoup
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.types.detection import GaussianDetection
    from stonesoup.types.hypothesis import SingleHypothesis
    from stonesoup.types.prediction import GaussianStatePrediction
    from stonesoup.updater.chernoff import ChernoffUpdater

    mm = LinearGaussian(ndim_state=2, mapping=(0, 1), noise_covar=np.array(A))
    rows = []
    for w in OMEGAS:
        up = ChernoffUpdater(measurement_model=mm, omega=w)
        pred = GaussianStatePrediction(np.array(b, float)[:, None], np.array(B))
        V = np.asarray(up.predict_measurement(pred, measurement_model=mm).covar, float)
        det = GaussianDetection(np.array(a, float)[:, None], np.array(A), measurement_model=mm)
        post = up.update(SingleHypothesis(pred, det))
        rows.append({"omega": w, "innovation_covariance": V.tolist(),
                     "posterior_mean": np.asarray(post.state_vector, float).ravel().tolist(),
                     "posterior_covariance": np.asarray(post.covar, float).tolist()})
    w = 0.8
    up = ChernoffUpdater(measurement_model=mm, omega=w)
    pred = GaussianStatePrediction(np.array(b, float)[:, None], np.array(B))
    det = GaussianDetection(np.array(a, float)[:, None], np.array(A2), measurement_model=mm)
    hyp = SingleHypothesis(pred, det)
    V = np.asarray(up.predict_measurement(pred, measurement_model=mm).covar, float)
    post = up.update(hyp)
    case = {"omega": w, "detection_covariance": A2, "innovation_covariance": V.tolist(),
            "posterior_mean": np.asarray(post.state_vector, float).ravel().tolist(),
            "posterior_covariance": np.asarray(post.covar, float).tolist()}
    return {"stonesoup_version": stonesoup.__version__, "date": date.today().isoformat(),
            "measurement": {"mean": a, "covariance": A}, "prediction": {"mean": b, "covariance": B}, "rows": rows,
            "detection_case": case}


if __name__ == "__main__":
    out = Path(__file__).resolve().parents[1] / "fusion" / "data" / "peers" / "stonesoup_chernoff.json"
    out.write_text(json.dumps(run(), indent=1) + "\n", encoding="utf-8")
    print(f"wrote {out}")
