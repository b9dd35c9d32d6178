"""glowkit: the worked example of a new kind of component (docs/new-component.rst).

The *Glow Board* is an imaginary board with four light sensors, a kind of component j5aio
does not have, and one distance sensor, a kind it has. It speaks a line protocol over a
serial port at 57600 baud; every command and every reply ends with ``\\n``:

=================  =======================  =============================================
command            reply                    meaning
=================  =======================  =============================================
``?``              ``GLOW:<version>``       who are you? (firmware ``1.x``)
``L<n>``           ``<lux>``                the light on sensor ``n`` (0 to 3), in lux
``G<n>``           ``<gain>``               the gain of sensor ``n``: 1, 4, 16 or 64
``G<n> <gain>``    ``OK``                   set the gain of sensor ``n``
``D``              ``<mm>`` or ``-``        the distance sensor's reading, in whole
                                            millimetres; ``-`` when nothing is in range
=================  =======================  =============================================

Anything else is answered ``ERR <why>``.
"""
