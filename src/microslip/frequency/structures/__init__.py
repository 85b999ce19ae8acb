"""Linear structures with contacts attached: :class:`~.structure.Structure`, one sector of a
bladed disk (:class:`~.cyclic.CyclicStructure`), the under-platform damper
(:class:`~.damper.UnderPlatformDamper`), mistuned disks assembled whole (:mod:`.mistuning`) and the
friction contacts of a reduced bolted joint (:func:`~.joints.jointed_structure`)."""
