"""The drawings and pictures of a robot: DOT and Mermaid graphs, the 3D scene, the shaded
picture and the browser viewer."""
