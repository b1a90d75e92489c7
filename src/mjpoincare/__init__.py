"""mjpoincare: analytic Poincare-map results of impacting systems, checked in MuJoCo."""
