"""erdesign: design, simulation and diagnosis of electro- and magnetorheological dampers with annular ducts."""

__version__ = "0.1.0"
