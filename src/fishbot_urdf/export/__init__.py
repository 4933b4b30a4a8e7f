"""What other programs read, made from a robot's analysis: `sdf` (SDF as sdformat's URDF
converter writes it)."""
