"""Time-domain stress laws of the fluid (SI kernels): the Makris elastic-viscoplastic law and its limits."""

__all__: list[str] = []
