"""Linear structures with contacts attached: :class:`~.structure.Structure`, one sector of a
bladed disk (:class:`~.cyclic.CyclicStructure`), the under-platform damper
(:class:`~.damper.UnderPlatformDamper`) and mistuned disks assembled whole (:mod:`.mistuning`)."""
