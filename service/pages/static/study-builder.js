// The study builder on the design-study page: a step's select submits its form when
// it changes (without JavaScript, the step's button does), and its button is hidden.
(function () {
  "use strict";
  var selects = document.querySelectorAll("select[data-autosubmit]");
  Array.prototype.forEach.call(selects, function (select) {
    var form = select.form;
    if (!form) {
      return;
    }
    var button = form.querySelector(".step-button");
    if (button) {
      button.hidden = true;
    }
    select.addEventListener("change", function () {
      if (select.value !== "") {
        form.submit();
      }
    });
  });
})();
