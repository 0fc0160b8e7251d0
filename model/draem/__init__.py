"""DRAEM anomaly detector over polarimetric priors: networks, anomaly synthesis, loss, training, metrics,
checkpoints. Plain torch; imports nothing from station, drivers or sim."""
