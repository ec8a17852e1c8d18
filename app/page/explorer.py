"""The page's controller: one session's features, their URL and their messages.

`Explorer` builds the features of one page, the contact (`app.contact.view`), the
Methods card (`app.methods`) and the Motor card (`app.motor`, built when first opened),
and holds what belongs to the page rather than to a feature: the URL (`app.page.url`:
sent with each change, written into the address bar by the browser a moment after the
last), the message banner (refused link values, the Motor card's refusals), the view
(the full page, or the one-screen presentation) and the session's end.  The layout
takes the features' views (`app.page.layout`, `app.page.presentation`); every number
comes from `core` through the features.
"""

from __future__ import annotations

import html
import io

import panel as pn
import param

from app.bem import BemCard
from app.contact import lesson
from app.contact.state import CONTACT_INPUTS, ExplorerState
from app.contact.view import ContactView
from app.dem.view import DemCard
from app.kit.a11y import expandable_card
from app.kit.style import MESSAGE_STYLE
from app.kit.widgets import LabelledCheckbox, shortened
from app.methods import MethodsScene
from app.motor import URL_PARAMS as MOTOR_URL_PARAMS
from app.motor import MotorScene
from app.page import layout, presentation, student, url
from app.page.describe import Describer
from core import Contact

URL_DELAY_S = 0.4  # the URL follows the parameters this long after the last change (s)

#: What the Motor card's "follow" box puts in the contact's state, and restores.
FOLLOWED = ("physical", "drive", "psi", "tau0", "mu", "nu")


def following_note(psi: float, tau0: float, mu: float, nu: float) -> str:
    """The banner's words while the plots follow the Motor card's rotor: why the contact's
    inputs changed, and how to get one's own back."""
    return (f"The plots above show the rotor's contact at x₀ (ψ = {psi:.4g}, τ₀ = "
            f"{tau0:.4g} rad, μ = {mu:.3g}, ν = {nu:.3g}); untick \"Show the rotor's "
            "contact\" in the Motor card to get your own contact back.")


class Explorer(param.Parameterized):
    """One user's page: the features, the URL, the messages."""

    def __init__(self, state: ExplorerState | None = None, query: dict | None = None) -> None:
        super().__init__()
        self.state = state or ExplorerState()
        parts = url.split(dict(query or {}))
        self.messages = url.apply_contact(self.state, parts.contact)
        #: the page shown: '' (everything) or 'present' (one screen)
        self.view_name, message = url.view_of(parts.view)
        self.messages += message
        self._motor_query = parts.motor  # (applied when the Motor card is built)
        #: the page's URL query, in the browser's address bar
        self.url_writer = url.UrlWriter(name="url_writer", delay_ms=round(URL_DELAY_S * 1000))
        self._url_query: dict[str, str] | None = None  # (the query it holds)
        self._own: dict | None = None  # the contact's inputs while it follows the rotor
        self._following = False  # (a change made by following, not by the user)

        self.contact = ContactView(self.state)
        self.methods = MethodsScene()
        self.dem = DemCard()  # (a contact of its own: the DEM test cases)
        self.bem = BemCard(self.state.current, self.state.tau)  # (built when first opened)
        self.methods.update_contact(self.state.current)
        self.motor: MotorScene | None = None  # built when its card is first opened
        self.follow_motor = LabelledCheckbox(
            label="Show the rotor's contact (at x₀) in the plots above", value=False)
        self.motor_card = expandable_card(title="Motor: the rod, its thrust and speed (Fig. 1)",
                                          collapsed=True, sizing_mode="stretch_width", margin=6)
        self.message = pn.pane.HTML("", visible=False, sizing_mode="stretch_width",
                                    name="query_message", styles=MESSAGE_STYLE)
        self.show_messages(self.messages)
        self.write_url()
        #: each plot's name and description, and the live region (`app.page.describe`)
        self.describer = Describer(self.contact, self.state)
        #: the contact as a lesson file that plays without a server (`app.contact.lesson`)
        self.lesson_download = pn.widgets.FileDownload(
            callback=self.lesson_file, filename="zharii_lesson.html",
            label="Download this lesson (works offline)", color="primary", width=310)
        self.connect()
        if self._motor_query:  # a link to the motor opens it
            self.motor_card.collapsed = False

    def connect(self) -> None:
        """Every subscription of the page (the contact's own are
        `app.contact.view.connect`; the Motor card's are made when it is built,
        `_on_motor_card`; the plots' descriptions follow the contact in
        `app.page.describe.Describer`)."""
        s = self.state
        # the other features follow the state's contact
        s.param.watch(lambda e: self.bem.update(e.new, s.tau), "current")
        s.param.watch(lambda e: self.bem.update(s.current, e.new), "tau")
        s.param.watch(lambda e: self.methods.update_contact(e.new), "current")
        # the Motor card: built when first opened; its rotor's contact shown when asked
        self.motor_card.param.watch(self._on_motor_card, "collapsed")
        self.follow_motor.param.watch(self._on_follow, "value")
        # the user's change of the contact: past messages done, the rotor no longer followed
        s.param.watch(self._on_inputs, list(CONTACT_INPUTS))
        # the URL: once per change (a move's parameters change in one batch)
        s.param.watch(lambda *_: self.write_url(),
                      [*CONTACT_INPUTS, "tau", "log_psi", "preset", "material"])

    # ---------------------------------------------------------------- messages

    def show_messages(self, messages: list[str]) -> None:
        """Show warnings (e.g. rejected URL values) above the plots; [] hides them.

        Messages quote what the user sent (the URL's values): they are shown as text,
        never as markup, long ones cut.  Unchanged messages are not sent again.
        """
        text = "<br>".join(html.escape(shortened(m))
                           for m in messages)
        if text != self.message.object or self.message.visible != bool(messages):
            self.message.param.update(object=text, visible=bool(messages))

    def _on_inputs(self, *events: param.parameterized.Event) -> None:
        """The user changed the contact: past messages are done; a contact that followed
        the rotor no longer does (the user took it over)."""
        self.show_messages([])
        if self.follow_motor.value and not self._following:
            self._own = None  # (nothing to restore: the user's own contact is on screen)
            self.follow_motor.value = False

    # ------------------------------------------------------------------- motor

    def _on_motor_card(self, event: param.parameterized.Event) -> None:
        """Build the Motor scene when its card is first opened."""
        if event.new or self.motor is not None:
            return
        self.motor = MotorScene()
        messages = self.motor.apply_query(self._motor_query)
        self.motor.on_contact(self._follow)
        self.motor.state.param.watch(lambda *_: self.write_url(), list(MOTOR_URL_PARAMS))
        self.motor_card.objects = [self.follow_motor, self.motor]
        if messages:  # the link's refused motor values
            self.show_messages([*self.messages, *messages])
        self.write_url()

    def _on_follow(self, event: param.parameterized.Event) -> None:
        """Ticked: the plots show the rotor's contact, the user's own kept; unticked:
        the user's own contact again."""
        if event.new:
            self._own = {k: getattr(self.state, k) for k in FOLLOWED}
            if self.motor is not None:
                self._follow(self.motor.contact)
        elif self._own is not None:
            own, self._own = self._own, None
            self._set_contact(own)
            self.show_messages(self.messages)

    def _follow(self, contact: tuple[float, float] | None) -> None:
        """The scenes above show the rotor's contact (psi, tau0 at x0; its mu, nu), when
        asked to."""
        if contact is None or not self.follow_motor.value or self.motor is None:
            return
        psi, tau0 = contact
        mu, nu = self.motor.state.mu, self.motor.motor.equivalent[2]  # (the pair's nu)
        try:
            Contact(psi, tau0, mu=mu, nu=nu)
        except ValueError as err:  # (e.g. a preload so light that tau0 rounds to pi/2)
            self.show_messages([*self.messages, f"The plots cannot follow the rotor's "
                                f"contact at x₀: {err}"])
            return
        self._set_contact(dict(physical=False, drive="psi", psi=psi, tau0=tau0, mu=mu, nu=nu))
        self.show_messages([*self.messages, following_note(psi, tau0, mu, nu)])

    def _set_contact(self, values: dict) -> None:
        self._following = True
        try:
            self.state.param.update(**values)
        finally:
            self._following = False

    # --------------------------------------------------------------------- URL

    def query(self) -> dict[str, str]:
        """The page's URL query: every feature's part and the view."""
        return url.join(self.state.query(),
                        self.motor.query() if self.motor is not None else {},
                        self.view_name)

    def write_url(self) -> None:
        """Put the parameters in the page's URL (`app.page.url.UrlWriter`): the query goes
        to the browser with the change that makes it, and the browser writes it into the
        address bar URL_DELAY_S after the last change (during a slider drag, once at its
        end: it would compete with the plots for the browser).  A query equal to the
        last one written is not written again (a move changes several parameters)."""
        query = self.query()
        if query != self._url_query:
            self._url_query = query
            self.url_writer.write(query=[[k, v] for k, v in query.items()])

    # ------------------------------------------------------------------ lesson

    def lesson_file(self) -> io.StringIO:
        """The lesson file of the contact on screen (`app.contact.lesson.lesson_html`), for
        the download button (made on the click; named after the contact)."""
        self.lesson_download.filename = lesson.file_name(self.state)
        return io.StringIO(lesson.lesson_html(self.state))

    # -------------------------------------------------------------------- page

    def view(self) -> pn.Column:
        """The page: `app.page.layout.page`, or the one-screen `app.page.presentation`
        view when the explorer was opened with view=present."""
        if self.view_name == presentation.VIEW:
            return presentation.presentation(self.contact, self.message,
                                             self.describer.descriptions,
                                             self.describer.announcer, [self.url_writer])
        if self.view_name == student.VIEW:
            return student.student(self.contact, self.message, self.describer.descriptions,
                                   self.describer.announcer, [self.url_writer])
        return layout.page(self.contact, self.message,
                           [self.contact.fig6_card, self.methods.view(), self.motor_card,
                            self.dem, self.bem], self.describer.descriptions,
                           self.describer.announcer, [self.url_writer],
                           teaching=[self.lesson_download, student.link()])

    def attach(self, shell: pn.Column, page: pn.Column | None = None) -> pn.Column:
        """Show `page` (default: `view()`) in the served `shell` (`app.page.guard.serve_shell`),
        in the session whose document is being filled: its end stops the explorer's
        runs."""
        page = page or self.view()
        shell.objects = [page]
        pn.state.on_session_destroyed(self.close)
        return page

    def close(self, session_context) -> None:
        """The session ended: stop the Methods, DEM and Motor runs."""
        self.methods.close()
        self.dem.close()
        self.bem.close()
        if self.motor is not None:
            self.motor.close()
