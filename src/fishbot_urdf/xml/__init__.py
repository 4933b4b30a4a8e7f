"""The XML reading: safe parsing as urdfdom reads a file, streaming, every element's place, and
the recovery of what TinyXML accepts and strict XML refuses."""
